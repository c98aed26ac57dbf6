#pragma once
// An operator's commissioning of one hardware axis that no job holds (netmc enable, disable,
// quick-stop, move, jog): the CiA 402 power-up, a hold in CSP where the axis stands, supervised
// point-to-point moves and jogs inside the axis's window and under its velocity limit, and the
// ramp down before the power stage is switched off. As LinuxCNC's and TwinCAT's manual modes do,
// a jog lasts only as long as its commands keep coming (a deadman), and the axis trips
// (quick stop) when it does not follow its profile.
//
// The node calls poll() on every exchange with the drive (every 2 ms while it moves, 10 ms while
// it holds); commands and polls run on the node's one thread.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "server/drive/axis_limits.hpp"
#include "server/drive/cia402.hpp"
#include "server/drive/drive.hpp"
#include "server/drive/point_to_point_move.hpp"

namespace netmc::axis {

struct CommissioningSettings {
  double velocity_m_s = 0.05;        // a move's speed when the operator names none
  double acceleration_m_s2 = 0.5;    // every ramp: moves, jogs, stops
  double enable_timeout_s = 5.0;     // Operation enabled within this of `enable`
  double jog_deadman_s = 0.5;        // a jog stops this long after its last command
  // Commanded minus actual position beyond this trips the axis (quick stop): the drive does not
  // follow (blocked, a wrong scale, a frozen encoder).
  double following_error_limit_m = 2e-3;
};

class CommissioningAxis {
 public:
  enum class Motion { off, enabling, holding, moving, jogging, stopping };

  CommissioningAxis(CommissioningSettings settings, drive::AxisLimits limits);

  // Each returns "" when taken, else why not (for the operator: names the limit or the state).
  std::string enable(double now_s);
  std::string move(double target_m, double speed_m_s, double now_s);
  std::string jog(double speed_m_s, double now_s);  // 0: stop the jog where the ramp ends
  // To rest on the settings' deceleration, then switched off; at once where nothing moves.
  void disable(drive::Drive& drive, double now_s);
  // The drive's own quick stop (0x605A), written now; commissioning ends.
  void quick_stop(drive::Drive& drive);
  // A job takes the axis over, or its drive is lost: commissioning ends without a write, saying
  // why where `note` does.
  void release(const std::string& note = "");

  // One exchange: reads the drive and writes what the motion needs now. Throws drive::DriveError.
  drive::DriveFeedback poll(drive::Drive& drive, double now_s);

  Motion motion() const { return motion_; }
  bool active() const { return motion_ != Motion::off; }
  bool moving() const { return motion_ == Motion::moving || motion_ == Motion::jogging || motion_ == Motion::stopping; }
  double following_error_m() const { return following_error_m_; }
  // How the last command ended when it ended otherwise than asked ("" while all is well).
  const std::string& note() const { return note_; }

 private:
  // A new profile to `target_m`, from where the axis is commanded to be now.
  void plan(double target_m, double speed_m_s, double now_s);
  // To rest on the acceleration limit from the commanded motion, inside the window.
  void plan_stop(double now_s);
  // Where the axis is commanded to be now and how fast: on its profile, or where it holds.
  std::pair<double, double> commanded(double now_s) const;

  CommissioningSettings settings_;
  drive::AxisLimits limits_;
  Motion motion_ = Motion::off;
  std::string note_;
  std::optional<drive::PointToPointMove> profile_;
  double profile_start_s_ = 0.0;
  double hold_m_ = 0.0;             // where the axis holds (holding), or the profile's end
  double jog_speed_m_s_ = 0.0;
  double jog_until_s_ = 0.0;
  double enable_until_s_ = 0.0;
  double last_position_m_ = 0.0;
  double following_error_m_ = 0.0;
  bool mode_written_ = false;
};

const char* motion_name(CommissioningAxis::Motion motion);

}  // namespace netmc::axis
