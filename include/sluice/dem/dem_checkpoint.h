#pragma once
// Checkpoint and restart of the DEM: everything the next step depends on, so
// that a run continued from a checkpoint on the same number of ranks repeats
// the uninterrupted run bit for bit, and on another number of ranks differs
// only by the order of floating-point sums.
//
// A checkpoint is a directory:
//   state          text: format, the scene entries it depends on, counters,
//                  wall positions and the scene's own records (output series,
//                  probes); written last, so a directory without it is not one
//   mesh*          the background cells, their partition over the ranks and
//                  the particles in them (deal.II/p4est serialization)
//   particles.bin  every particle by id: position, velocities, force, torque,
//                  coupling data, and every tangential history
//   rank-<r>.bin   each rank's arrays in their order, its neighbour list with
//                  histories and the positions at the last build (used when
//                  restarting on the same number of ranks)
// It is written as '<name>.writing' and renamed when complete: a run killed
// at any moment leaves the previous checkpoints intact.

#include <sluice/dem/dem_system.h>

#include <functional>
#include <string>
#include <vector>

namespace sluice
{
  /// When the next checkpoint is due: every 'checkpoint/step interval' steps
  /// or 'time interval' seconds, counted from t = 0 also after a restart.
  class CheckpointSchedule
  {
  public:
    CheckpointSchedule(const SceneParameters &p, double time);
    bool due(unsigned long long step, double time, double dt);

  private:
    unsigned long long step_interval;
    double             time_interval, next_time = 0.;
  };

  /// Removes the oldest checkpoints of the base name of 'newest' (a
  /// checkpoint_path()) beyond 'keep', in its directory.
  void prune_checkpoints(const std::string &newest, unsigned int keep);

  /// '<directory>/<base>-checkpoint-<step, 10 digits>'.
  std::string checkpoint_path(const std::string &directory, const std::string &base,
                              unsigned long long step);

  /// What a scene built on the DEM (a coupled scene) adds to its checkpoint:
  /// the entries of its own that the state depends on ('name = value' lines,
  /// checked on restart like the DEM's), and a collective writer of its own
  /// files into the checkpoint directory (called before 'state' is written, so
  /// they are part of the one atomic rename; their sizes are recorded).
  struct CheckpointAddition
  {
    std::vector<std::string>                       signature;
    std::function<void(const std::string &directory)> write;
  };

  /// Collective. Writes the checkpoint 'path' of the DEM's current state, with
  /// the scene's records (lines without newlines), then removes the oldest
  /// checkpoints of the same base name beyond 'keep'. Throws OutputError.
  void save_dem_checkpoint(const DemSystem &dem, const std::string &path,
                           const std::vector<std::string> &scene_records, unsigned int keep,
                           const CheckpointAddition &addition = {});

  /// Collective. Replaces the DEM's state by the checkpoint's and returns the
  /// scene's records. Throws InputError (exit 2, nothing written) naming the
  /// file and what is wrong: missing, cut short, damaged, or written by a
  /// scene whose particles, materials, contact law, domain, walls or time step
  /// differ.
  /// 'signature': the scene's own entries, as given to save_dem_checkpoint.
  std::vector<std::string> load_dem_checkpoint(DemSystem &dem, const std::string &path,
                                               const std::vector<std::string> &signature = {});

  /// The checkpoint 'restart from' names: a directory, or 'latest' for the
  /// newest complete checkpoint of 'base' in 'directory'. Throws InputError.
  std::string find_checkpoint(const std::string &restart_from, const std::string &directory,
                              const std::string &base, const std::string &file_name);
} // namespace sluice
