// The SCENE.json tests' files: a folder in the temporary directory holding the texts given,
// and the message a file is refused with.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"

namespace scene_json_files {

/// The 1 m floor quad most of them include, as an OBJ file.
inline constexpr const char* kFloorObj = "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nf 1 2 3 4\n";

/// Writes each (file name, text) into the folder `folder` of the temporary directory (made if
/// need be) and returns the path of the last file.
inline std::string write_files(const std::string& folder,
                               const std::vector<std::pair<std::string, std::string>>& files) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / folder;
    std::filesystem::create_directories(dir);
    std::filesystem::path last;
    for (const auto& [name, text] : files) {
        last = dir / name;
        std::ofstream(last) << text;
    }
    return last.string();
}

/// The message of the InputError that loading `path` gives, or "" when it loads.
inline std::string load_error(const std::string& path) {
    try {
        hemirad::load_scene_json(path);
    } catch (const hemirad::InputError& e) {
        return e.what();
    }
    return "";
}

} // namespace scene_json_files
