#pragma once
// netmc's simulated drive (--drive sim:PLANT): an EmulatedDrive in virtual time, called
// directly. netmc sim runs it in-process, netmc-axis behind DDS; both through SupervisedAxis, so
// a lockstep run over DDS gives netmc sim's numbers bit for bit.

#include <memory>
#include <string>

#include "server/drive/drive.hpp"
#include "server/drive/emulated_drive.hpp"

namespace netmc::drive {

class SimulatedDrive final : public Drive {
 public:
  SimulatedDrive(std::unique_ptr<plant::AxisPlant> plant, std::string name, EmulatedDriveSettings settings = {});

  std::string describe() const override { return name_; }
  bool virtual_time() const override { return true; }
  void open() override { drive_.power_up(); }
  void close() noexcept override {}
  void write_controlword(std::uint16_t word) override { drive_.apply_controlword(word); }
  void write_mode(OperationMode mode) override { drive_.set_mode(mode); }
  void write_target(OperationMode mode, double value) override { drive_.set_target(mode, value); }
  DriveFeedback read() override;
  void cycle(double time_s) override { drive_.advance_to(time_s); }
  bool restart_at(double position_m) override {
    drive_.restart_at(position_m);
    return true;
  }
  void write_quick_stop_deceleration(double deceleration_m_s2) override {
    drive_.set_quick_stop_deceleration(deceleration_m_s2);
  }

  const EmulatedDrive& emulated() const { return drive_; }

 private:
  EmulatedDrive drive_;
  std::string name_;
};

}  // namespace netmc::drive
