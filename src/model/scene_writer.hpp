#pragma once
// A scene written back as a scene file (the Python module's Scene.save and the commands it runs on
// a Scene edited in memory, docs/python.md): the JSON text it was read from (Scene::source_text),
// its relative paths rebased to the new file's folder, and each value edited since written over
// the file's own in SI units with their unit (the shortest text that reads back bit for bit). A
// bar whose material was edited carries it inline (a material file is never written). The text is
// read back before it is returned: one that would give another scene is refused (InputError),
// e.g. an edit of a value the scene's `calibration` replaces whenever the file is read.
#include <filesystem>
#include <string>

#include "model/scene.hpp"

namespace shpb {

// The scene's JSON text as a scene file at `file`.
std::string scene_file_text(const Scene& scene, const std::filesystem::path& file);

// Writes it to `file` atomically. An existing file is replaced only with `overwrite`, and then
// only a file that reads as a scene, and not one the scene reads (its own scene file may be): never
// a measured record, a table, a material or calibration file.
void save_scene(const Scene& scene, const std::filesystem::path& file, bool overwrite);

// `written`, a path relative to `from_dir` as a scene gives it, relative to `to_dir` instead.
std::string rebased_path(const std::string& written, const std::filesystem::path& from_dir,
                         const std::filesystem::path& to_dir);

}  // namespace shpb
