// What libhemirad exports. The library is built with -fvisibility=hidden: only declarations
// marked HEMIRAD_API (the public API in include/hemirad/) are visible to programs that link
// it; everything else in src/ stays inside the library (programs in this tree that need it,
// the tests and two of the tools, link the private static library hemirad_internal instead).
// The pattern is Magnum's (src/Magnum/GL/visibility.h): one macro, switched by whether the
// library itself is being compiled (HEMIRAD_BUILDING_LIBRARY, set by CMakeLists.txt).
#pragma once

#if defined(HEMIRAD_BUILDING_LIBRARY)
/// Exported from libhemirad (compiling the library).
#define HEMIRAD_API __attribute__((visibility("default")))
#else
/// Imported from libhemirad (compiling a program that uses it). On ELF the import needs no
/// attribute; default visibility keeps a program built with -fvisibility=hidden able to
/// share the types (exceptions, virtual classes) with the library.
#define HEMIRAD_API __attribute__((visibility("default")))
#endif

/// Hidden even inside an exported class (a pimpl's Impl, private helpers).
#define HEMIRAD_LOCAL __attribute__((visibility("hidden")))
