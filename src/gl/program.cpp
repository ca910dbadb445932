#include "gl/program.h"

#include <string>
#include <vector>

#include "hemirad/error.h"

namespace hemirad::gl {

namespace {

GLenum stage_of(std::string_view file) {
    const auto ends_with = [&](std::string_view suffix) { return file.ends_with(suffix); };
    if (ends_with(".vert")) return GL_VERTEX_SHADER;
    if (ends_with(".frag")) return GL_FRAGMENT_SHADER;
    if (ends_with(".geom")) return GL_GEOMETRY_SHADER;
    if (ends_with(".comp")) return GL_COMPUTE_SHADER;
    throw RuntimeError("shader " + std::string(file) +
                       ": unknown stage (expected .vert, .frag, .geom or .comp)");
}

std::string shader_log(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), &length, log.data());
    log.resize(static_cast<std::size_t>(length));
    return log;
}

std::string program_log(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), &length, log.data());
    log.resize(static_cast<std::size_t>(length));
    return log;
}

/// Mesa and NVIDIA start each line of a log with source string 0 ("0:8(26): error", "0(8) :
/// error"); put the file name in its place, so that editors can jump to it.
std::string with_file_name(const std::string& log, std::string_view file) {
    std::string out;
    std::size_t start = 0;
    while (start < log.size()) {
        std::size_t end = log.find('\n', start);
        end = end == std::string::npos ? log.size() : end + 1;
        const std::string_view line(log.data() + start, end - start);
        if (line.size() > 1 && line[0] == '0' && (line[1] == ':' || line[1] == '('))
            out.append(file).append(line.substr(1));
        else
            out.append(line);
        start = end;
    }
    return out;
}

Shader compile(std::string_view file) {
    const GLenum stage = stage_of(file);
    const char* source = embedded_shader(file);
    if (!source)
        throw RuntimeError("shader " + std::string(file) +
                           " is not among the embedded shaders (is it in shaders/?)");
    Shader shader = Shader::create(stage);
    glShaderSource(shader.id(), 1, &source, nullptr);
    glCompileShader(shader.id());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok)
        throw RuntimeError("shader " + std::string(file) + " failed to compile:\n" +
                           with_file_name(shader_log(shader.id()), file));
    return shader;
}

} // namespace

Program link_program(std::initializer_list<std::string_view> shader_files) {
    std::vector<Shader> shaders;
    std::string names;
    for (std::string_view file : shader_files) {
        shaders.push_back(compile(file));
        names += (names.empty() ? "" : ", ") + std::string(file);
    }
    Program program = Program::create();
    for (const Shader& shader : shaders) glAttachShader(program.id(), shader.id());
    glLinkProgram(program.id());
    for (const Shader& shader : shaders) glDetachShader(program.id(), shader.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok)
        throw RuntimeError("program (" + names + ") failed to link:\n" + program_log(program.id()));
    return program;
}

} // namespace hemirad::gl
