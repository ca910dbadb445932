// Internal: the backends behind hemirad::gl::Context. Each lives in its own .cpp so that the
// EGL and OSMesa headers never meet.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "hemirad/gl/context.h"

namespace hemirad::gl::detail {

/// Each creates a context, makes it current and loads GL through load_gl(); on failure they
/// throw hemirad::RuntimeError naming the call that failed, and leave nothing behind.
std::unique_ptr<Context> create_egl_context(const ContextOptions& options, bool debug);
std::unique_ptr<Context> create_osmesa_context(const ContextOptions& options, bool debug);

std::vector<std::string> egl_device_names();

/// Loads GL entry points with `load` (glad's pointers are process-wide, so every new context
/// reloads them for its backend). Throws on failure.
void load_gl(GLADloadfunc load, const char* backend);

/// Turns on GL_DEBUG_OUTPUT(_SYNCHRONOUS) with a callback that prints errors and warnings
/// (not notifications) to stderr. Needs a current context.
void enable_debug_output();

} // namespace hemirad::gl::detail
