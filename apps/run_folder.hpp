// A run's output folder (runout run --out DIR): what is in it, what a run may do to it, and
// the two checkpoints. Everything here is decided before the first file is written or deleted,
// so a folder is always a complete result, a resumable partial one (checkpoint and scene), or
// untouched (docs/reliability.md).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace runout::app {

// The files of a run in DIR. Results that appear during a run (dump and VTK frames, snapshots in DIR)
// are staged in DIR/.partial and published with the others at the end, summary.json last.
struct RunFolder {
  explicit RunFolder(std::string dir);
  std::string dir, scene, summary, timeseries, checkpoint, previous_checkpoint, staging, dump;
  std::string vtk;          // ParaView frames (runout run --vtk-every) and their frames.pvd
  std::string states;       // whole states at chosen t* (runout run --states), checkpoints
  std::string preparation;  // the pile's settle report, so a resumed run reports it too
};

// A folder a run will write into (OUT, --frames, --snapshot-dir) must be a folder or not exist
// yet, and the nearest existing folder above it must be writable; a file (--movie) must not be
// a folder and its folder must be writable. Throws UsageError naming the option.
void check_folder_writable(const std::string& path, const std::string& option);
void check_file_writable(const std::string& path, const std::string& option);

struct ResumePoint {
  std::string path;    // the checkpoint used
  std::string bytes;
};

// What a run will do to its folder, decided from what the folder holds.
struct FolderPlan {
  bool clear = false;                 // remove runout's own files of an earlier run first
  std::optional<ResumePoint> resume;  // --resume with a checkpoint of this scene
  std::vector<std::string> notes;     // said on stderr (fallback to the previous checkpoint, ...)
};

// `key` is the scene's physics key (io::physics_key); `decode` tries a checkpoint's bytes and
// throws IoError if it is damaged or of another scene. Throws UsageError (another scene's
// results without --overwrite, an unfinished run without --resume) or IoError (no usable
// checkpoint to resume from, each one named with what is wrong with it).
using CheckpointTrial = std::function<void(const std::string& bytes, const std::string& path)>;
FolderPlan plan_folder(const RunFolder& f, std::uint64_t key, bool resume, bool overwrite,
                       const CheckpointTrial& decode);

// The files plan_folder clears: runout's own, and nothing else.
void clear_own_files(const RunFolder& f);

// Writes DIR/checkpoint.bin, keeping the one before as checkpoint.prev.bin (both written
// atomically and synced), so a checkpoint damaged on disk still leaves one to resume from.
void write_checkpoint(const RunFolder& f, const std::string& bytes);

// Moves the staged results into DIR (dump frames, snapshots) and removes the staging folder.
void publish_staged(const RunFolder& f);

}  // namespace runout::app
