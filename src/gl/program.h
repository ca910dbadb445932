// GLSL programs from the shader files in shaders/, embedded into the binary at build time
// (cmake/embed_shaders.cmake). Uniforms and inputs take explicit `layout(location = N)` in
// the shaders: no lookups by name.
#pragma once

#include <initializer_list>
#include <string_view>

#include "gl/objects.h"

namespace hemirad::gl {

/// The text of shaders/<name> (e.g. "smoke.frag"), or null when there is no such file.
/// Defined in the generated embedded_shaders.cpp.
const char* embedded_shader(std::string_view name);

/// Compiles each file (stage from its extension: .vert, .frag, .geom, .comp) and links them.
/// Throws hemirad::RuntimeError: for an unknown file or extension naming it, for a compile
/// error naming the file with the info log, for a link error naming all files with the log.
Program link_program(std::initializer_list<std::string_view> shader_files);

} // namespace hemirad::gl
