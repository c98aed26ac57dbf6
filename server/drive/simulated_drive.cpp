#include "server/drive/simulated_drive.hpp"

#include <cmath>

namespace netmc::drive {

SimulatedDrive::SimulatedDrive(std::unique_ptr<plant::AxisPlant> plant, std::string name,
                               EmulatedDriveSettings settings)
    : drive_(std::move(plant), settings), name_(std::move(name)) {}

DriveFeedback SimulatedDrive::read() {
  DriveFeedback feedback;
  feedback.position_m = drive_.position();
  feedback.velocity_m_s = drive_.velocity();
  if (!std::isfinite(feedback.position_m) || !std::isfinite(feedback.velocity_m_s)) drive_.check_model();
  feedback.has_velocity = true;
  feedback.statusword = drive_.statusword();
  feedback.error_code = drive_.error_code();
  return feedback;
}

}  // namespace netmc::drive
