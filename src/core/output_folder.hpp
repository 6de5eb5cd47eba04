#pragma once
// Results are written into a temporary folder beside DIR and renamed into place at the end, so a
// failed or interrupted run leaves the previous DIR intact and no half-written result
// (docs/outputs.md (conventions)). Files the program did not write are never deleted: an existing
// DIR is replaced only if it is empty or shpb wrote it — it holds the marker file `.shpb-output`
// (signature line, command, the names shpb wrote, each file's digest) and nothing the marker does
// not list, each file as shpb wrote it (an edited one is the user's). A folder
// that is, holds or lies inside an input of the run is refused. A DIR that is a symbolic link is
// written through (the link stays, its target is replaced). Every file is fsync'ed before the one
// atomic exchange of the two folders; temporaries of runs that were killed outright are removed by
// the next run into the same DIR when they are provably shpb's (exact name with this host's tag,
// dead pid, and for a folder its marker naming host and pid, or a whole shpb result: killed while
// committing).
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/interrupt.hpp"  // commit() throws Interrupted once a signal arrived

namespace shpb {

// The marker's first line; a folder is shpb's only if its marker starts with exactly this line.
inline constexpr const char* kOutputMarker = ".shpb-output";
inline constexpr const char* kOutputMarkerSignature =
    "shpb output folder: written by shpb, replaced only by shpb";
// The marker of a temporary folder while a run writes it (host and pid; never in a result).
inline constexpr const char* kTemporaryMarker = ".shpb-temporary";

class OutputFolder {
 public:
  // Checks that `final_dir` can be written and may be replaced (throws InputError otherwise) and
  // creates the temporary folder. `command` is recorded in the marker; `inputs` are the files and
  // folders the run reads (scene, material and signal files, a plan, its parts, a campaign): DIR
  // may be none of them, nor hold one, nor lie inside an input folder. Every command declares its
  // inputs here, the one check.
  explicit OutputFolder(std::filesystem::path final_dir, std::string command = "",
                        const std::vector<std::filesystem::path>& inputs = {});
  ~OutputFolder();  // removes the temporary folder unless commit() succeeded
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return temp_; }  // write files here
  std::filesystem::path file(const std::string& name) const { return temp_ / name; }
  const std::filesystem::path& final_path() const { return final_; }

  // Writes the marker, fsyncs every file, then moves the temporary folder to its final place
  // (replacing a previous shpb result); throws Interrupted instead if SIGINT/SIGTERM arrived, so
  // an interrupted run changes nothing, and WriteError if a file cannot be made durable.
  void commit();

  // The files of the previous result found as shpb wrote them, by their marker's digest line:
  // their size and time of change then (output_folder.cpp, edited_file).
  using Verified =
      std::map<std::string, std::pair<std::uintmax_t, std::filesystem::file_time_type>>;

 private:
  void placed(const std::optional<std::filesystem::path>& previous);

  std::filesystem::path final_;
  std::filesystem::path temp_;
  std::filesystem::path created_;  // the outermost parent folder this run made, if any
  std::string command_;
  bool committed_ = false;
  Verified verified_;
};

// One output file written atomically (e.g. `dispersion -o FILE`): written to a temporary file in
// the same folder, fsync'ed and renamed over FILE by commit(); FILE keeps its previous content
// until then, also when the process is killed. With a `header`, an existing FILE is replaced only
// if it is empty or its first line starts with it: a file shpb wrote (docs/outputs.md,
// Conventions); anything else is refused (InputError) before any work.
class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path final_file, const std::string& header = "");
  ~OutputFile();  // removes the temporary file unless commit() succeeded
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::filesystem::path& path() const { return temp_; }  // write here
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  std::filesystem::path created_;  // the outermost parent folder this run made, if any
  bool committed_ = false;
};

// `text` (an error message) with every temporary folder or file of this process named by the
// output it stands for: "DIR/field.csv: cannot be written", not ".DIR.tmp-…/field.csv".
std::string final_names(const std::string& text);

}  // namespace shpb
