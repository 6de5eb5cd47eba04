#pragma once
// Results are written into a temporary folder beside DIR and renamed into place at the end, so a
// failed or interrupted run leaves the previous DIR intact and no half-written result
// (docs/outputs.md (conventions)). Files the program did not write are never deleted: an existing DIR is replaced
// only if it is empty or was written by shpb (it holds a summary.json). The replacement is one
// atomic exchange of the two folders where the file system supports it; temporary folders of
// runs that were killed outright are removed by the next run into the same DIR.
#include <filesystem>

namespace shpb {

class OutputFolder {
 public:
  // Checks that `final_dir` can be written (throws InputError otherwise) and creates the
  // temporary folder.
  explicit OutputFolder(std::filesystem::path final_dir);
  ~OutputFolder();  // removes the temporary folder unless commit() succeeded
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return temp_; }  // write files here
  std::filesystem::path file(const std::string& name) const { return temp_ / name; }
  const std::filesystem::path& final_path() const { return final_; }

  // Moves the temporary folder to its final place (replacing a previous shpb result); throws
  // Interrupted instead if SIGINT/SIGTERM arrived, so an interrupted run changes nothing.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Interruption (SIGINT, SIGTERM): install once in main; long loops poll interrupted() and throw
// shpb::Interrupted so that OutputFolder's destructor cleans up. A second signal ends the
// process at once.
void install_interrupt_handlers();
bool interrupted();

}  // namespace shpb
