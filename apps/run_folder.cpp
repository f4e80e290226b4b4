#include "run_folder.hpp"

#include <cstdint>
#include <filesystem>
#include <system_error>
#include <unistd.h>

#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"

namespace runout::app {

namespace fs = std::filesystem;

namespace {

bool path_present(const std::string& path) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(path, ec));  // a dangling symlink counts: it is named, not skipped
}

// The nearest folder at or above `path` that exists: where a new folder or file would be made.
fs::path nearest_existing(fs::path p) {
  std::error_code ec;
  p = fs::absolute(p, ec);
  while (!p.empty() && !fs::exists(p, ec)) {
    if (p == p.parent_path()) break;
    p = p.parent_path();
  }
  return p;
}

void check_creatable_under(const fs::path& target, const std::string& option) {
  std::error_code ec;
  const fs::path base = nearest_existing(target);
  if (!fs::is_directory(base, ec))
    throw UsageError(option + ": cannot create " + target.string() + ": " + base.string() + " is not a folder");
  if (::access(base.c_str(), W_OK | X_OK) != 0)
    throw UsageError(option + ": cannot write into " + base.string() + " (permission denied or read-only)");
}

bool is_own_snapshot(const std::string& name) {
  if (name.rfind("snapshot_t", 0) != 0 || name.size() <= 14) return false;
  const std::string ext = name.substr(name.size() - 4);
  return ext == ".png" || ext == ".pdf" || ext == ".svg";
}

bool is_own_state(const std::string& name) {
  return name.rfind("state_t", 0) == 0 && name.size() > 11 && name.substr(name.size() - 4) == ".bin";
}

}  // namespace

RunFolder::RunFolder(std::string d)
    : dir(std::move(d)),
      scene(dir + "/scene.resolved.toml"),
      summary(dir + "/summary.json"),
      timeseries(dir + "/timeseries.csv"),
      checkpoint(dir + "/checkpoint.bin"),
      previous_checkpoint(dir + "/checkpoint.prev.bin"),
      staging(dir + "/.partial"),
      dump(dir + "/dump"),
      vtk(dir + "/vtk"),
      states(dir + "/states"),
      preparation(dir + "/preparation.json") {}

void check_folder_writable(const std::string& path, const std::string& option) {
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (fs::exists(st) && !fs::is_directory(st))
    throw UsageError(option + ": " + path + " exists and is not a folder");
  if (fs::is_directory(st)) {
    if (::access(path.c_str(), W_OK | X_OK) != 0)
      throw UsageError(option + ": cannot write into " + path + " (permission denied or read-only)");
    return;
  }
  check_creatable_under(path, option);
}

void check_file_writable(const std::string& path, const std::string& option) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw UsageError(option + ": " + path + " is a folder, not a file name");
  const fs::path p(path);
  if (p.filename().empty()) throw UsageError(option + ": \"" + path + "\" names no file");
  check_creatable_under(p.has_parent_path() ? p.parent_path() : fs::path("."), option);
}

namespace {

bool holds_own_files(const RunFolder& f) {
  std::error_code ec;
  for (const std::string& p : {f.scene, f.summary, f.timeseries, f.checkpoint, f.previous_checkpoint,
                               f.staging, f.dump, f.vtk, f.states, f.preparation})
    if (path_present(p)) return true;
  for (const auto& e : fs::directory_iterator(f.dir, ec))
    if (is_own_snapshot(e.path().filename().string())) return true;
  return false;
}

std::optional<std::uint64_t> folder_scene_key(const RunFolder& f) {
  try {
    return io::physics_key(io::read_scene_file(f.scene));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

FolderPlan plan_folder(const RunFolder& f, std::uint64_t key, bool resume, bool overwrite,
                       const CheckpointTrial& decode) {
  FolderPlan plan;
  std::error_code ec;
  const bool own = fs::is_directory(f.dir, ec) && holds_own_files(f);
  const std::optional<std::uint64_t> folder_key = own ? folder_scene_key(f) : std::nullopt;
  const bool same_scene = folder_key && *folder_key == key;
  const bool has_checkpoint = path_present(f.checkpoint) || path_present(f.previous_checkpoint);

  if (resume && has_checkpoint) {
    std::vector<std::string> why;
    for (const std::string& path : {f.checkpoint, f.previous_checkpoint}) {
      if (!path_present(path)) continue;
      try {
        std::string bytes = io::read_regular_file(path, UINTMAX_MAX);
        decode(bytes, path);
        if (!why.empty())
          plan.notes.push_back("warning: " + why.front() + "; resuming from the previous checkpoint " + path);
        plan.resume = ResumePoint{path, std::move(bytes)};
        return plan;
      } catch (const IoError& e) {
        why.push_back(e.what());
      }
    }
    std::string all;
    for (const auto& w : why) all += (all.empty() ? "" : "; ") + w;
    throw IoError("cannot resume: " + all +
                  ". Resume with the scene that wrote it, or run without --resume and with "
                  "--overwrite to start afresh");
  }
  if (own && !same_scene && !overwrite)
    throw UsageError(f.dir + " holds the results of another scene (its scene.resolved.toml " +
                     (folder_key ? "has other physics" : "is missing or unreadable") +
                     "): choose another --out, or add --overwrite to replace them (only runout's "
                     "own files are removed)");
  if (own && same_scene && !overwrite && !resume && has_checkpoint && !path_present(f.summary))
    throw UsageError(f.dir + " holds an unfinished run of this scene: add --resume to continue "
                     "it, or --overwrite to start afresh");
  if (resume) plan.notes.push_back("no checkpoint in " + f.dir + ": starting from the beginning");
  plan.clear = own;
  return plan;
}

void clear_own_files(const RunFolder& f) {
  std::error_code ec;
  // summary.json first: from here on the folder is not a complete result.
  for (const std::string& p : {f.summary, f.timeseries, f.checkpoint, f.previous_checkpoint, f.scene, f.preparation})
    fs::remove(p, ec);
  for (const std::string& d : {f.staging + "/dump", f.staging + "/vtk", f.staging + "/states", f.staging, f.dump,
                               f.vtk, f.states}) {
    for (const auto& e : fs::directory_iterator(d, ec)) {
      const std::string name = e.path().filename().string();
      const bool frame = name.rfind("frame.", 0) == 0 &&
                         (e.path().extension() == ".lammpstrj" || e.path().extension() == ".vtp");
      if (frame || name == "frames.pvd" || is_own_snapshot(name) || is_own_state(name))
        fs::remove(e.path(), ec);
    }
    fs::remove(d, ec);  // only if now empty: a user's own file in it stays
  }
  for (const auto& e : fs::directory_iterator(f.dir, ec))
    if (is_own_snapshot(e.path().filename().string())) fs::remove(e.path(), ec);
}

void write_checkpoint(const RunFolder& f, const std::string& bytes) {
  std::error_code ec;
  if (fs::exists(f.checkpoint, ec)) {
    fs::rename(f.checkpoint, f.previous_checkpoint, ec);
    if (ec) throw IoError("cannot keep " + f.checkpoint + " as " + f.previous_checkpoint + ": " + ec.message());
  }
  io::write_file_atomically(f.checkpoint, bytes);
}

void publish_staged(const RunFolder& f) {
  std::error_code ec;
  if (!fs::is_directory(f.staging, ec)) return;
  auto move = [](const fs::path& from, const fs::path& to) {
    std::error_code e;
    fs::rename(from, to, e);
    if (e) throw IoError("cannot move " + from.string() + " to " + to.string() + ": " + e.message());
  };
  for (const auto& e : fs::directory_iterator(f.staging, ec)) {
    const fs::path to = fs::path(f.dir) / e.path().filename();
    if (e.is_directory() && fs::is_directory(to)) {
      // Merged, not replaced: a resumed run that had already ended stages an empty folder,
      // and must not take the published frames or states with it.
      for (const auto& inner : fs::directory_iterator(e.path())) move(inner.path(), to / inner.path().filename());
      fs::remove(e.path(), ec);
    } else {
      fs::remove_all(to, ec);
      move(e.path(), to);
    }
  }
  fs::remove(f.staging, ec);
}

}  // namespace runout::app
