#include "core/output_folder.hpp"

#include <fcntl.h>  // AT_FDCWD
#include <signal.h>
#include <stdio.h>  // renameat2
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <fstream>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <system_error>

#include "core/checked_write.hpp"
#include "core/error.hpp"
#include "core/file_digest.hpp"
#include "core/interrupt.hpp"

namespace shpb {
namespace fs = std::filesystem;

namespace {
// The temporaries of this scheme: ".<name>.tmp-<pid>-<host>-<random>", <host> the 16 hex digits
// of the FNV-1a of this host's name (core/file_digest.hpp) so that a folder shared between
// machines never has its pids judged by the wrong host; a folder also holds kTemporaryMarker
// (signature, host, pid), and ".old" is the twin holding a previous result while it is replaced.
constexpr const char* kTemporarySignature =
    "shpb temporary output: removed once its process is gone";
constexpr std::size_t kRandomDigits = 5;

std::string temp_prefix(const fs::path& final_path) {
  std::string prefix = ".";
  prefix += final_path.filename().string();
  prefix += ".tmp-";
  return prefix;
}

const std::string& host_name() {
  static const std::string name = [] {
    char buffer[256] = {};
    if (::gethostname(buffer, sizeof buffer - 1) != 0) return std::string("unknown-host");
    return std::string(buffer);
  }();
  return name;
}

std::string host_tag() { return digest_text(fnv1a64(host_name())); }

bool all_digits(std::string_view s, std::size_t max) {
  return !s.empty() && s.size() <= max &&
         s.find_first_not_of("0123456789") == std::string_view::npos;
}

// The pid in "<prefix><pid>-<host>-<random>[.old]" if the name is exactly of our scheme and
// `host` is this host's tag; names that merely look alike are not ours and are left alone.
std::optional<pid_t> temp_owner(const std::string& name, const std::string& prefix) {
  if (name.rfind(prefix, 0) != 0) return std::nullopt;
  std::string_view rest = std::string_view(name).substr(prefix.size());
  if (rest.size() > 4 && rest.substr(rest.size() - 4) == ".old") rest.remove_suffix(4);
  const auto dash = rest.find('-');
  if (dash == std::string_view::npos) return std::nullopt;
  const std::string_view pid_text = rest.substr(0, dash), after = rest.substr(dash + 1);
  const std::string tag = host_tag();
  if (after.size() <= tag.size() + 1 || after.substr(0, tag.size()) != tag ||
      after[tag.size()] != '-' || !all_digits(after.substr(tag.size() + 1), kRandomDigits) ||
      !all_digits(pid_text, 9))
    return std::nullopt;
  long pid = 0;
  std::from_chars(pid_text.data(), pid_text.data() + pid_text.size(), pid);
  if (pid <= 0) return std::nullopt;
  return static_cast<pid_t>(pid);
}

// The marker of a temporary of process `pid` on this host.
std::string temporary_marker_text(pid_t pid) {
  return std::string(kTemporarySignature) + "\nhost: " + host_name() +
         "\npid: " + std::to_string(pid) + "\n";
}

// The marker's line of a file shpb wrote: "fnv1a64: <16 hex digits> <path in the folder>"
// (core/file_digest.hpp). A file the user edited since no longer has it: it is not shpb's to
// replace. Markers without these lines (an older shpb's) are judged by their names alone.
constexpr const char* kDigestLine = "fnv1a64: ";
constexpr std::size_t kDigestDigits = 16;

// The digest lines of every regular file under `dir` (sub-folders too), in the order of their
// paths. Markers are bookkeeping, not results: the temporary's own, and a sub-folder's
// .shpb-output, which `report` extends when it draws that sub-folder (docs/commands.md, report).
std::string digest_lines(const fs::path& dir) {
  std::set<std::string> files;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (it->is_regular_file(ec) && !it->is_symlink(ec) && name != kOutputMarker &&
        name != kTemporaryMarker)
      files.insert(it->path().lexically_relative(dir).string());
  }
  std::string lines;
  for (const auto& name : files)
    if (const auto digest = file_digest(dir / name))
      lines += kDigestLine + digest_text(*digest) + " " + name + "\n";
  return lines;
}

// A file a marker's digest line records: the line (without its prefix), the digest's text and the
// file's path in the folder.
struct RecordedFile {
  std::string line, digest;
  fs::path path;
};

// The file `line` (a digest line without its prefix) records; none for a malformed line or a path
// leading out of the folder, which is no file of it.
std::optional<RecordedFile> recorded_file(const std::string& line) {
  if (line.size() <= kDigestDigits + 1 || line[kDigestDigits] != ' ') return std::nullopt;
  fs::path path = fs::path(line.substr(kDigestDigits + 1)).lexically_normal();
  if (path.is_absolute() || path.empty() || *path.begin() == "..") return std::nullopt;
  return RecordedFile{line, line.substr(0, kDigestDigits), std::move(path)};
}

// The file `r` of `dir` whose digest no longer holds: one the user edited, or replaced by
// something else; "" if it holds, or the file is gone (nothing of the user's is lost then). A file
// found as written is kept in `verified` by its size and time of change: one run looks at its DIR
// up to three times, and a file unchanged since (an edit changes its time) is not read again.
std::string edited_file(const fs::path& dir, const RecordedFile& r,
                        OutputFolder::Verified* verified) {
  const fs::path& name = r.path;
  const std::string& line = r.line;
  std::error_code ec;
  const auto type = fs::symlink_status(dir / name, ec).type();
  if (type == fs::file_type::not_found) return "";
  if (type != fs::file_type::regular) return name.string();
  const auto stamp = std::pair{fs::file_size(dir / name, ec), fs::last_write_time(dir / name, ec)};
  const auto seen = verified ? verified->find(line) : OutputFolder::Verified::iterator{};
  if (verified && seen != verified->end() && seen->second == stamp && !ec) return "";
  const auto digest = file_digest(dir / name);
  if (!digest || digest_text(*digest) != r.digest) return name.string();
  if (verified && !ec) (*verified)[line] = stamp;
  return "";
}

std::string added_file(const fs::path& dir, const std::vector<RecordedFile>& recorded,
                       OutputFolder::Verified* verified);

// Why shpb may not replace `dir`, or "" if it may: it is empty, or its marker starts with the
// signature and lists every entry the folder holds, each file as shpb wrote it (its digest).
std::string refusal(const fs::path& dir, OutputFolder::Verified* verified = nullptr) {
  std::error_code ec;
  if (fs::is_empty(dir, ec)) return "";
  const fs::path marker = dir / kOutputMarker;
  if (!fs::is_regular_file(fs::symlink_status(marker, ec)))
    return "is not empty and holds no " + std::string(kOutputMarker) +
           " marker: shpb replaces only folders it wrote (a result of an older shpb has no "
           "marker: delete it yourself) — choose another output folder";
  std::ifstream in(marker);
  std::string line;
  if (!std::getline(in, line) || line != kOutputMarkerSignature)
    return std::string(kOutputMarker) + " is not shpb's marker; refusing to replace the folder";
  std::set<std::string> listed;
  std::vector<RecordedFile> recorded;
  bool has_digests = false;  // a marker of this shpb, not an older one's of names alone
  while (std::getline(in, line)) {
    if (line.rfind("file: ", 0) == 0) listed.insert(line.substr(6));
    if (line.rfind(kDigestLine, 0) != 0) continue;
    has_digests = true;
    if (auto r = recorded_file(line.substr(std::strlen(kDigestLine)))) recorded.push_back(*r);
  }
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name != kOutputMarker && !listed.count(name))
      return "holds " + name +
             ", which shpb did not write; refusing to replace the folder (move it away or "
             "choose another output folder)";
  }
  if (ec) return "cannot be listed: " + ec.message();
  for (const auto& r : recorded)
    if (const std::string name = edited_file(dir, r, verified); !name.empty())
      return "holds " + name +
             ", which was changed since shpb wrote it; refusing to replace the folder (move it "
             "away or choose another output folder)";
  if (has_digests) return added_file(dir, recorded, verified);
  return "";
}

// Why shpb may not replace `dir`'s sub-folders, or "": each file under them is one its digest
// lines record (a file the user put into figures/, say, is not shpb's to delete). A sub-folder
// with a marker of its own (a campaign's test, which `report` may have drawn since) is judged by
// that marker. A marker without digest lines (an older shpb's) is judged by its names alone.
std::string added_file(const fs::path& dir, const std::vector<RecordedFile>& recorded,
                       OutputFolder::Verified* verified) {
  std::set<std::string> paths;
  for (const auto& r : recorded) paths.insert(r.path.string());
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!fs::is_directory(e.symlink_status(ec))) continue;
    if (fs::is_regular_file(fs::symlink_status(e.path() / kOutputMarker, ec))) {
      if (std::string why = refusal(e.path(), verified); !why.empty())
        return e.path().filename().string() + "/: " + why;
      continue;
    }
    for (auto it = fs::recursive_directory_iterator(e.path(), ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (fs::is_directory(it->symlink_status(ec))) continue;
      const std::string name = it->path().lexically_relative(dir).lexically_normal().string();
      if (it->path().filename() != kOutputMarker && !paths.count(name))
        return "holds " + name +
               ", which shpb did not write; refusing to replace the folder (move it away or "
               "choose another output folder)";
    }
  }
  return ec ? "cannot be listed: " + ec.message() : "";
}

// Throws unless shpb may replace `dir` (refusal): a folder, empty or a whole shpb result.
void refuse_to_replace(const fs::path& dir, OutputFolder::Verified* verified = nullptr) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec)))
    throw input_error(dir.string(), "", "", "exists and is not a folder");
  if (const std::string why = refusal(dir, verified); !why.empty())
    throw input_error(dir.string(), "", "", why);
}

// The folder is provably a temporary of process `pid` on this host: its marker names this host
// and that pid; or the process was killed while creating it (make_temporary: the folder, then its
// marker in one write), so it holds nothing, or only a marker cut short — a prefix of that text;
// or it was killed while committing (OutputFolder::commit), and the folder is a whole shpb result
// (the new one before the exchange, the previous one after it), one shpb may replace.
bool provably_temporary(const fs::path& folder, pid_t pid) {
  const std::string expected = temporary_marker_text(pid);
  std::error_code ec;
  if (refusal(folder).empty()) return true;
  std::size_t entries = 0;
  for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator();
       it.increment(ec))
    ++entries;
  if (ec) return false;
  const fs::path marker = folder / kTemporaryMarker;
  if (!fs::is_regular_file(fs::symlink_status(marker, ec))) return false;
  std::ifstream in(marker);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string found = text.str();
  return found == expected || (entries == 1 && expected.rfind(found, 0) == 0);
}

// Removes a temporary folder (this run's, or one provably_temporary), its marker last: a run
// killed in the middle (a second Ctrl-C) leaves a folder the next run still knows as a temporary.
void remove_temporary(const fs::path& folder) {
  std::error_code ec;
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(folder, ec))
    if (e.path().filename() != kTemporaryMarker) entries.push_back(e.path());
  for (const auto& e : entries) fs::remove_all(e, ec);
  fs::remove_all(folder, ec);
}

// Removes the previous result once replaced, marked first as this run's temporary, so that a run
// killed while removing it leaves a folder the next run removes (whole, it is shpb's anyway).
void mark_and_remove(const fs::path& folder) {
  try {
    write_text_file(folder / kTemporaryMarker, temporary_marker_text(::getpid()));
  } catch (const WriteError&) {  // unmarked, it is left for the user: nothing is lost
    return;
  }
  remove_temporary(folder);
}

// Temporaries left by a run that was killed outright (SIGKILL, power loss) are removed when the
// next run starts, and only what is provably shpb's: the exact name of the scheme with this
// host's tag, a pid no process has now, and for a folder the marker naming this host and that pid
// (or, killed while the folder was being made, nothing but a marker cut short; killed while
// committing, a whole shpb result).
// Anything else (".res.tmp-2024-05-01.tar", a backup) is the user's and stays.
void remove_stale_temporaries(const fs::path& final_path) {
  const std::string prefix = temp_prefix(final_path);
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(final_path.parent_path(), ec)) {
    const auto pid = temp_owner(e.path().filename().string(), prefix);
    if (!pid || ::kill(*pid, 0) == 0 || errno != ESRCH) continue;
    std::error_code rm;
    const auto type = fs::symlink_status(e.path(), rm).type();
    if (type == fs::file_type::regular)
      fs::remove(e.path(), rm);
    else if (type == fs::file_type::directory && provably_temporary(e.path(), *pid))
      remove_temporary(e.path());
  }
}

// A field of /proc/self/mountinfo as written: space, tab, newline and backslash as "\ooo".
std::string mountinfo_field(const std::string& field) {
  std::string text;
  for (std::size_t i = 0; i < field.size(); ++i) {
    if (field[i] == '\\' && i + 3 < field.size() && all_digits(field.substr(i + 1, 3), 3)) {
      text += static_cast<char>(std::stoi(field.substr(i + 1, 3), nullptr, 8));
      i += 3;
    } else {
      text += field[i];
    }
  }
  return text;
}

// An existing output is renamed over at the end, which a mount point refuses ("Device or resource
// busy", after all the work): true if `output` is one. /proc/self/mountinfo lists every mount
// point (its fifth field), a bind mount of a folder of the same device too; without it, a mount
// point is on another device than its parent.
bool is_mount_point(const fs::path& output) {
  std::error_code ec;
  const fs::path real = fs::canonical(output, ec);
  if (ec) return false;
  if (std::ifstream mounts("/proc/self/mountinfo"); mounts) {
    for (std::string line; std::getline(mounts, line);) {
      std::istringstream fields(line);
      std::string id, parent, device, root, mount_point;
      if (fields >> id >> parent >> device >> root >> mount_point &&
          fs::path(mountinfo_field(mount_point)) == real)
        return true;
    }
    return false;
  }
  struct stat output_stat {
  }, parent_stat{};
  return ::stat(real.c_str(), &output_stat) == 0 &&
         ::stat(real.parent_path().c_str(), &parent_stat) == 0 &&
         output_stat.st_dev != parent_stat.st_dev;
}

// `inner` is `outer` or lies inside it (both canonical).
bool contains(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i)
    if (i == inner.end() || *o != *i) return false;
  return true;
}

fs::path make_temporary(const fs::path& final_path, bool folder) {
  std::random_device rd;
  std::error_code ec;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path candidate =  // hidden sibling: ".<name>.tmp-<pid>-<host>-<random>"
        final_path.parent_path() / (temp_prefix(final_path) + std::to_string(::getpid()) + "-" +
                                    host_tag() + "-" + std::to_string(rd() % 100000));
    if (folder) {
      if (fs::create_directory(candidate, ec)) {
        try {
          write_text_file(candidate / kTemporaryMarker, temporary_marker_text(::getpid()));
        } catch (...) {
          fs::remove_all(candidate, ec);
          throw;
        }
        return candidate;
      }
    } else {
      const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      if (fd >= 0) {
        ::close(fd);
        return candidate;
      }
      if (errno != EEXIST) throw_write_error(candidate, errno);
    }
  }
  throw input_error(final_path.parent_path().string(), "", "", "cannot create a temporary output");
}

// The absolute path of an output (DIR or FILE).
fs::path absolute_output(const fs::path& given, const std::string& what) {
  std::error_code ec;
  if (given.empty()) throw input_error("-o", "", "\"\"", "an output " + what + " is required");
  fs::path absolute = fs::absolute(given, ec);
  if (ec) throw input_error(given.string(), "", "", "cannot resolve the output " + what);
  if (!absolute.has_filename()) absolute = absolute.parent_path();
  // "-o .", "-o dir/..": the folder itself by its real name, so that its temporary is made
  // beside it, not inside it (the exchange of a folder with its own child fails after the run).
  if (absolute.filename() == "." || absolute.filename() == "..") {
    absolute = fs::weakly_canonical(absolute, ec);
    if (ec) throw input_error(given.string(), "", "", "cannot resolve the output " + what);
    if (!absolute.has_filename()) absolute = absolute.parent_path();
  }
  // A symbolic link is written through: the link stays, its target receives the result (replaced
  // atomically beside the target, docs/commands.md); a link to nothing is refused.
  if (fs::is_symlink(absolute, ec)) {
    const fs::path target = fs::canonical(absolute, ec);
    if (ec)
      throw input_error(given.string(), "", "",
                        "is a symbolic link to a missing " + what + " (" +
                            fs::read_symlink(absolute, ec).string() +
                            "): create the target or choose another output " + what);
    return target;
  }
  return absolute;
}

// Creates the output's parent folder if needed and checks that it is writable.
// Returns the outermost folder it created ("" if none), for remove_created_parents.
fs::path prepare_parent(const fs::path& output) {
  std::error_code ec;
  const fs::path parent = output.parent_path();
  fs::path created;
  if (!fs::is_directory(parent, ec)) {
    for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
      created = p;
      if (p == p.parent_path()) break;
    }
    fs::create_directories(parent, ec);
    if (ec) throw input_error(parent.string(), "", "", "output parent folder cannot be created");
  }
  if (::access(parent.c_str(), W_OK) != 0)
    throw input_error(parent.string(), "", "", "output parent folder is not writable");
  return created;
}

// A run that writes nothing leaves nothing, not even the parent folders it made for its output
// (those still empty: another run's temporary in one keeps it).
void remove_created_parents(const fs::path& output, const fs::path& created) {
  if (created.empty()) return;
  std::error_code ec;
  for (fs::path p = output.parent_path(); fs::remove(p, ec) && p != created; p = p.parent_path()) {
  }
}
}  // namespace

std::string final_names(const std::string& text) {
  // Each "/.<name>.tmp-<pid>-<host>-<random>" of this process becomes "/<name>"; a segment of
  // the path ends at "/" or at the ":" that follows a path in a message.
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find_first_of("/:", at), text.size());
    const std::string segment = text.substr(at, end - at);
    const std::size_t tmp = segment.rfind(".tmp-");
    if (segment.size() > 1 && segment[0] == '.' && tmp != std::string::npos && tmp > 1 &&
        temp_owner(segment, segment.substr(0, tmp + 5)) == ::getpid())
      out += segment.substr(1, tmp - 1);
    else
      out += segment;
    if (end < text.size()) out += text[end];
    at = end + 1;
  }
  return out;
}

OutputFolder::OutputFolder(fs::path final_dir, std::string command,
                           const std::vector<fs::path>& inputs)
    : command_(std::move(command)) {
  std::error_code ec;
  final_ = absolute_output(final_dir, "folder");
  if (fs::exists(final_, ec) && !fs::is_directory(final_, ec))
    refuse_to_replace(final_);  // names what it is
  // An input of the run inside DIR would be deleted by the exchange (or DIR is one); DIR inside
  // an input folder (a plan's parts) would change what the run reads.
  const fs::path real_dir = fs::weakly_canonical(final_, ec);
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    std::error_code input_ec;
    const fs::path real_input = fs::weakly_canonical(fs::absolute(input, input_ec), input_ec);
    if (input_ec) continue;
    const bool inside = fs::is_directory(real_input, input_ec) && contains(real_input, real_dir);
    if (contains(real_dir, real_input) || inside)
      throw input_error(final_.string(), "", "",
                        std::string(inside ? "lies inside" : "is or holds") +
                            " an input of this run (" + input.string() +
                            "): choose an output folder apart from the run's inputs");
  }
  if (fs::exists(final_, ec)) {
    refuse_to_replace(final_, &verified_);
    if (is_mount_point(final_))
      throw input_error(final_.string(), "", "",
                        "is a mount point, which cannot be replaced: write into a folder inside "
                        "it");
  }
  created_ = prepare_parent(final_);
  remove_stale_temporaries(final_);
  temp_ = make_temporary(final_, true);
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  if (!temp_.empty()) remove_temporary(temp_);
  remove_created_parents(final_, created_);
}

void OutputFolder::commit() {
  throw_if_interrupted();  // asked to stop: keep the previous result
  std::string marker = std::string(kOutputMarkerSignature) + "\ncommand: " + command_ + "\n";
  std::error_code ec;
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(temp_, ec))
    names.insert(e.path().filename().string());
  names.erase(kTemporaryMarker);  // the result holds only what the command wrote
  for (const auto& name : names) marker += "file: " + name + "\n";
  marker += digest_lines(temp_);
  // The output marker before the temporary's is removed: a run killed from here on leaves a
  // folder that is provably shpb's either way, which the next run removes.
  write_text_file(temp_ / kOutputMarker, marker);
  fs::remove(temp_ / kTemporaryMarker, ec);
  sync_tree(temp_);  // durable before it becomes the result
  // Two runs into a new DIR at once: the other may put its result there between the look and the
  // move; this one then replaces it (both are whole results; the last one stays).
  for (int attempt = 0; attempt < 100; ++attempt) {
    if (!fs::exists(final_, ec)) {
      if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_NOREPLACE) == 0)
        return placed(std::nullopt);
      if (errno == EEXIST || errno == ENOTEMPTY) continue;
      if (errno != EINVAL && errno != ENOSYS) throw_write_error(final_, errno);
      fs::rename(temp_, final_, ec);  // a file system without renameat2's flags
      if (ec) throw_write_error(final_, ec.value());
      return placed(std::nullopt);
    }
    // DIR was checked when the run started; the user may have put a file into it since (a
    // long study): checked again, and the folder it swapped out once more, so that it is never
    // the user's that is removed.
    refuse_to_replace(final_, &verified_);
    // One atomic exchange where the file system offers it: DIR is never missing, not even for
    // an instant; the previous result ends up in the temporary folder and is removed with it.
    if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) == 0) {
      if (const std::string why = refusal(temp_, &verified_); !why.empty()) {
        ::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE);
        throw input_error(final_.string(), "", "", why);
      }
      return placed(temp_);
    }
    const fs::path old = temp_.string() + ".old";
    fs::rename(final_, old, ec);
    if (ec) throw_write_error(final_, ec.value());
    if (const std::string why = refusal(old, &verified_); !why.empty()) {
      fs::rename(old, final_, ec);
      throw input_error(final_.string(), "", "", why);
    }
    fs::rename(temp_, final_, ec);
    if (ec) {
      const int error = ec.value();
      fs::rename(old, final_, ec);
      throw_write_error(final_, error);
    }
    return placed(old);
  }
  throw_write_error(final_, EBUSY);  // 100 other runs in between: give up, nothing replaced
}

// The result is in place; `previous`, the folder holding the previous result, is removed.
void OutputFolder::placed(const std::optional<fs::path>& previous) {
  committed_ = true;
  sync_path(final_.parent_path());
  if (previous) mark_and_remove(*previous);
}

OutputFile::OutputFile(fs::path final_file, const std::string& header) {
  // "-o table/" names a folder: not a file "table" made in its stead.
  if (!final_file.empty() && !final_file.has_filename())
    throw input_error(final_file.string(), "", "", "names a folder: a file name was expected");
  final_ = absolute_output(final_file, "file");
  std::error_code ec;
  if (fs::is_directory(final_, ec))
    throw input_error(final_.string(), "", "", "is a folder: a file name was expected");
  if (fs::exists(final_, ec) && !fs::is_regular_file(final_, ec))
    throw input_error(final_.string(), "", "", "exists and is not a regular file");
  if (fs::exists(final_, ec) && is_mount_point(final_))
    throw input_error(final_.string(), "", "",
                      "is a mount point, which cannot be replaced: choose another file");
  if (!header.empty() && fs::exists(final_, ec) && fs::file_size(final_, ec) > 0) {
    std::ifstream in(final_, std::ios::binary);
    std::string first(header.size(), '\0');
    in.read(first.data(), static_cast<std::streamsize>(first.size()));
    if (first != header)
      throw input_error(final_.string(), "", "",
                        "exists and does not start with \"" + header +
                            "\": shpb replaces only a file it wrote (move it away or choose "
                            "another file)");
  }
  created_ = prepare_parent(final_);
  remove_stale_temporaries(final_);
  temp_ = make_temporary(final_, false);
}

OutputFile::~OutputFile() {
  if (committed_) return;
  std::error_code ec;
  if (!temp_.empty()) fs::remove(temp_, ec);
  remove_created_parents(final_, created_);
}

void OutputFile::commit() {
  throw_if_interrupted();
  sync_path(temp_);
  if (::rename(temp_.c_str(), final_.c_str()) != 0) throw_write_error(final_, errno);
  committed_ = true;
  sync_path(final_.parent_path());
}

}  // namespace shpb
