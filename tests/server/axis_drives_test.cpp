// The drives of a node's axes: where each axis's limits come from (the flags, the drive's own
// configuration, a simulated drive's plant rating), the refusal of a drive that is not simulated
// and has none, the plant its simulated drives and its jobs share, and the node's own plant
// overrides on top of a job's.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "plant/plant_catalog.hpp"
#include "server/axis/axis_drives.hpp"
#include "server/drive/drive_spec.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::axis {
namespace {

std::string refusal(const std::function<void()>& act) {
  try {
    act();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(accepted)";
}

TEST(AxisDrives, ASimulatedDriveTakesItsPlantsTravelAndRatedInputUnlessAFlagSaysOtherwise) {
  const auto specs = drive::parse_drive_flags({}, {"x", "y"}, "linmotor");
  drive::AxisLimits x_flags;
  x_flags.command = 4.0;
  const auto drives = open_axis_drives(specs, {{"x", x_flags}}, {});
  const plant::PlantRating rating = plant::plant_rating("linmotor");
  EXPECT_EQ(drives.at("x").limits.command, 4.0);  // the flag
  EXPECT_EQ(drives.at("y").limits.command, rating.rated_input);
  EXPECT_EQ(drives.at("y").limits.command, 10.0);  // the thesis's +-10 V
  EXPECT_EQ(drives.at("x").limits.position_min_m, -0.25);  // its 500 mm of travel
  EXPECT_EQ(drives.at("x").limits.position_max_m, 0.25);
  EXPECT_TRUE(std::isinf(drives.at("x").limits.velocity_m_s));
  EXPECT_FALSE(drives.at("x").hardware);
}

TEST(AxisDrives, AHardwareDriveThatCannotBeOpenedRefusesTheStart) {
  const auto specs = drive::parse_drive_flags({"x=plugin:/nonexistent/drive.so"}, {"x"}, "seed001");
  // The plugin cannot even be loaded: named with its path.
  EXPECT_NE(refusal([&] { open_axis_drives(specs, {}, {}); }).find("/nonexistent/drive.so"), std::string::npos);
}

TEST(AxisDrives, TheNodesPlantIsItsSimulatedDrivesAndItsJobs) {
  EXPECT_EQ(node_plant(drive::parse_drive_flags({"sim:ballscrew"}, {"x"}, "ballscrew"), ""), "ballscrew");
  EXPECT_EQ(node_plant(drive::parse_drive_flags({}, {"x"}, "seed001"), ""), "seed001");
  EXPECT_NE(refusal([] { node_plant(drive::parse_drive_flags({"sim:ballscrew"}, {"x"}, "ballscrew"), "hiwin"); })
                .find("one plant"),
            std::string::npos);
  EXPECT_NE(refusal([] {
              open_axis_drives(drive::parse_drive_flags({"sim:seed001:payload=3"}, {"x"}, "seed001"), {}, {});
            }).find("plant seed001 has no parameter 'payload'"),
            std::string::npos);
}

// sim:seed001:coulomb_m_s2=0 on axis y: the job's own y settings stay, the node's come after
// them (the later value of a key wins), x is untouched.
TEST(AxisDrives, TheNodesOverridesComeOnTopOfTheJobs) {
  netmc::v1::JobSpec spec;
  spec.set_plant("seed001");
  auto& y = *spec.add_plant_axes();
  y.set_axis("y");
  auto& load = *y.add_parameters();
  load.set_key("coulomb_m_s2");
  load.set_value(0.2);
  AxisDrive drive;
  drive.spec = drive::parse_drive_spec("sim:seed001:coulomb_m_s2=0");
  const auto changed = with_node_overrides(spec, "y", drive);
  ASSERT_EQ(changed.plant_axes_size(), 1);
  ASSERT_EQ(changed.plant_axes(0).parameters_size(), 2);
  EXPECT_EQ(changed.plant_axes(0).parameters(1).key(), "coulomb_m_s2");
  EXPECT_EQ(changed.plant_axes(0).parameters(1).value(), 0.0);
  const auto on_x = with_node_overrides(spec, "x", drive);
  ASSERT_EQ(on_x.plant_axes_size(), 2);
  EXPECT_EQ(on_x.plant_axes(1).axis(), "x");
  AxisDrive plain;
  plain.spec = drive::parse_drive_spec("sim:seed001");
  EXPECT_EQ(with_node_overrides(spec, "y", plain).SerializeAsString(), spec.SerializeAsString());
}

}  // namespace
}  // namespace netmc::axis
