// The compact flag syntax: units, shapes, delay and loss forms, and the error messages.
#include <gtest/gtest.h>

#include "client/spec_syntax.hpp"
#include "server/job/controller_registry.hpp"

namespace netmc::cli {
namespace {

std::string error_of(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(SpecSyntax, QuantitiesAreSiUnlessSuffixed) {
  EXPECT_DOUBLE_EQ(parse_quantity("10mm", Quantity::length, "f"), 0.01);
  EXPECT_DOUBLE_EQ(parse_quantity("250um", Quantity::length, "f"), 250e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("0.02", Quantity::length, "f"), 0.02);
  EXPECT_DOUBLE_EQ(parse_quantity("0.8ms", Quantity::time, "f"), 0.8e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("300us", Quantity::time, "f"), 300e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("8s", Quantity::time, "f"), 8.0);
  EXPECT_NE(error_of([] { parse_quantity("10ms", Quantity::length, "--trajectory r"); })
                .find("--trajectory r: expected a length"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_quantity("fast", Quantity::time, "--sample-period"); })
                .find("--sample-period"),
            std::string::npos);
  EXPECT_FALSE(error_of([] { parse_quantity("nan", Quantity::plain, "x"); }).empty());
}

TEST(SpecSyntax, Trajectories) {
  const auto circle = parse_trajectory("circle:r=10mm,cx=50mm,cy=50mm,period=8s");
  ASSERT_TRUE(circle.has_circle());
  EXPECT_DOUBLE_EQ(circle.circle().radius_m(), 0.01);
  EXPECT_DOUBLE_EQ(circle.circle().center_x_m(), 0.05);
  EXPECT_DOUBLE_EQ(circle.circle().period_s(), 8.0);
  const auto ellipse = parse_trajectory("ellipse:a=20mm,b=5mm,cx=0,cy=0,period=4s");
  EXPECT_DOUBLE_EQ(ellipse.ellipse().semi_axis_x_m(), 0.02);
  EXPECT_DOUBLE_EQ(ellipse.ellipse().semi_axis_y_m(), 0.005);
  const auto line = parse_trajectory("line:x0=0,y0=0,x1=40mm,y1=30mm,duration=5s");
  EXPECT_DOUBLE_EQ(line.line().x1_m(), 0.04);
  EXPECT_DOUBLE_EQ(line.line().duration_s(), 5.0);

  EXPECT_NE(error_of([] { parse_trajectory("spiral:r=1"); }).find("unknown shape 'spiral'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_trajectory("circle:r=10mm,period=8s,q=1"); })
                .find("unknown key 'q'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_trajectory("circle:cx=1"); }).find("missing key 'r'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_trajectory("circle:r"); }).find("expected key=value"),
            std::string::npos);
}

TEST(SpecSyntax, ContourLibraryTrajectories) {
  const auto figure = parse_trajectory("lissajous:ax=20mm,ay=15mm,p=3,q=2,period=12s,phase=0.3,cx=50mm,cy=40mm");
  ASSERT_TRUE(figure.has_lissajous());
  EXPECT_DOUBLE_EQ(figure.lissajous().amplitude_x_m(), 0.02);
  EXPECT_DOUBLE_EQ(figure.lissajous().amplitude_y_m(), 0.015);
  EXPECT_EQ(figure.lissajous().frequency_x(), 3u);
  EXPECT_EQ(figure.lissajous().frequency_y(), 2u);
  EXPECT_DOUBLE_EQ(figure.lissajous().phase_rad(), 0.3);
  EXPECT_DOUBLE_EQ(figure.lissajous().center_y_m(), 0.04);
  EXPECT_DOUBLE_EQ(figure.lissajous().period_s(), 12.0);
  EXPECT_FALSE(figure.lissajous().has_feed());
  const auto fed = parse_trajectory("lissajous:ax=20mm,ay=15mm,p=3,q=2,feed=15mm/s,amax=20mm/s2");
  EXPECT_DOUBLE_EQ(fed.lissajous().feed().feed_m_s(), 0.015);
  EXPECT_DOUBLE_EQ(fed.lissajous().feed().max_normal_acceleration_m_s2(), 0.02);
  EXPECT_DOUBLE_EQ(fed.lissajous().feed().max_tangential_acceleration_m_s2(), 0.0);  // = amax

  const auto ellipse = parse_trajectory("ellipse:a=20mm,b=5mm,feed=20mm/s,amax=30mm/s2,at=0.1");
  EXPECT_DOUBLE_EQ(ellipse.ellipse().feed().feed_m_s(), 0.02);
  EXPECT_DOUBLE_EQ(ellipse.ellipse().feed().max_tangential_acceleration_m_s2(), 0.1);
  EXPECT_DOUBLE_EQ(ellipse.ellipse().period_s(), 0.0);
  EXPECT_FALSE(parse_trajectory("ellipse:a=20mm,b=5mm,period=8s").ellipse().has_feed());

  const auto square = parse_trajectory("polyline:points=0,0;20mm,0;20mm,10mm;0,10mm;0,0,vmax=10mm/s,amax=50mm/s^2,corner=2mm/s");
  ASSERT_TRUE(square.has_polyline());
  ASSERT_EQ(square.polyline().points_size(), 5);
  EXPECT_DOUBLE_EQ(square.polyline().points(2).x_m(), 0.02);
  EXPECT_DOUBLE_EQ(square.polyline().points(2).y_m(), 0.01);
  EXPECT_DOUBLE_EQ(square.polyline().max_speed_m_s(), 0.01);
  EXPECT_DOUBLE_EQ(square.polyline().max_acceleration_m_s2(), 0.05);
  EXPECT_DOUBLE_EQ(square.polyline().corner_speed_m_s(), 0.002);
  // The points may also come last, and SI values need no suffix.
  const auto last = parse_trajectory("polyline:vmax=0.01,amax=0.05,points=0,0;0.01,0");
  EXPECT_EQ(last.polyline().points_size(), 2);
  EXPECT_DOUBLE_EQ(last.polyline().points(1).x_m(), 0.01);

  const auto spline = parse_trajectory("spline:points=0,0;30mm,-5mm;50mm,10mm;0,0,feed=20mm/s,amax=0.05m/s2,at=100mm/s2");
  ASSERT_TRUE(spline.has_spline());
  EXPECT_EQ(spline.spline().points_size(), 4);
  EXPECT_DOUBLE_EQ(spline.spline().points(1).y_m(), -0.005);
  EXPECT_DOUBLE_EQ(spline.spline().feed().feed_m_s(), 0.02);
  EXPECT_DOUBLE_EQ(spline.spline().feed().max_normal_acceleration_m_s2(), 0.05);
  EXPECT_DOUBLE_EQ(spline.spline().feed().max_tangential_acceleration_m_s2(), 0.1);

  const auto error = [](const char* text) { return error_of([&] { parse_trajectory(text); }); };
  EXPECT_NE(error("lissajous:ax=20mm,ay=15mm,p=1.5,q=2,period=8s").find("--trajectory p: expected a positive whole number"),
            std::string::npos);
  EXPECT_NE(error("lissajous:ax=20mm,ay=15mm,p=3,q=0,period=8s").find("--trajectory q"), std::string::npos);
  EXPECT_NE(error("lissajous:ax=20mm,ay=15mm,p=3,q=2").find("missing key 'period'"), std::string::npos);
  EXPECT_NE(error("lissajous:ax=20mm,ay=15mm,p=3,q=2,period=8s,feed=1mm/s,amax=1mm/s2").find("not both"),
            std::string::npos);
  EXPECT_NE(error("ellipse:a=20mm,b=5mm,period=8s,amax=1").find("ellipse takes period"), std::string::npos);
  EXPECT_NE(error("polyline:points=0,0;10mm,vmax=1mm/s,amax=1mm/s2").find("--trajectory points: point 2: expected X,Y"),
            std::string::npos);
  EXPECT_NE(error("polyline:points=0,0;10mm,0,0,vmax=1mm/s,amax=1mm/s2").find("point 2"), std::string::npos);
  EXPECT_NE(error("polyline:points=0,0;10cm,0,vmax=1mm/s,amax=1mm/s2").find("point 2 x: expected a length"),
            std::string::npos);
  EXPECT_NE(error("polyline:vmax=1mm/s,amax=1mm/s2").find("missing key 'points'"), std::string::npos);
  EXPECT_NE(error("polyline:points=0,0;1mm,0,vmax=1mm,amax=1mm/s2").find("--trajectory vmax: expected a speed"),
            std::string::npos);
  EXPECT_NE(error("spline:points=0,0;1mm,0,feed=1mm/s,amax=5ms").find("--trajectory amax: expected an acceleration"),
            std::string::npos);
  EXPECT_NE(error("spline:points=0,0;1mm,0,feed=1mm/s").find("missing key 'amax'"), std::string::npos);
  // A stray value without a key is still refused outside a list.
  EXPECT_NE(error("spline:feed=1mm/s,2,points=0,0;1mm,0,amax=1").find("expected key=value"), std::string::npos);
}

TEST(SpecSyntax, DelaysAndLosses) {
  const auto uniform = parse_delay("uniform:min=0.3ms,max=0.8ms", "--delay");
  EXPECT_DOUBLE_EQ(uniform.uniform().min_s(), 0.3e-3);
  EXPECT_DOUBLE_EQ(uniform.uniform().max_s(), 0.8e-3);
  EXPECT_DOUBLE_EQ(parse_delay("constant:1ms", "--delay").constant_s(), 1e-3);
  EXPECT_TRUE(parse_delay("none", "--delay").has_none());
  EXPECT_EQ(parse_delay("trace:delays.csv", "--delay").trace().path(), "delays.csv");
  const auto markov = parse_delay("markov:good=0.3ms..0.8ms,bad=3ms..12ms,p_gb=0.02,p_bg=0.2", "--delay");
  EXPECT_DOUBLE_EQ(markov.markov().bad().max_s(), 12e-3);
  EXPECT_DOUBLE_EQ(markov.markov().p_bad_to_good(), 0.2);
  EXPECT_DOUBLE_EQ(parse_delay("pareto:scale=0.2ms,shape=1.5", "--delay").pareto().shape(), 1.5);
  EXPECT_DOUBLE_EQ(parse_delay("normal:mean=1ms,sd=0.2ms", "--delay").normal().stddev_s(), 2e-4);
  EXPECT_DOUBLE_EQ(parse_loss("bernoulli:p=0.01", "--loss").bernoulli().p(), 0.01);
  EXPECT_DOUBLE_EQ(parse_loss("gilbert:p_gb=0.01,p_bg=0.3", "--loss").gilbert_elliott().loss_in_bad(), 1.0);

  EXPECT_NE(error_of([] { parse_delay("gamma:k=2", "--delay"); }).find("--delay: unknown delay 'gamma'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_delay("constant", "--delay"); }).find("constant:DURATION"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_delay("markov:good=1ms,bad=2ms..3ms,p_gb=0.1,p_bg=0.1", "--delay"); })
                .find("MIN..MAX"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_loss("burst:p=1", "--uplink-loss"); }).find("--uplink-loss"),
            std::string::npos);
}

// The gains flags are the registry's groups' (server/job/controller_gains.hpp).
const job::GainGroup& group(const std::string& name) { return *job::ControllerRegistry::global().gain_group(name); }

TEST(SpecSyntax, Gains) {
  const std::vector<std::string> axes{"x", "y"};
  netmc::v1::ControllerSpec spec;
  job::parse_gain_flag("r0=150,w0=120,observer=zoh,y.b0=1.8", group("adrc"), axes, spec);
  const auto& adrc = spec.gains().at("adrc");
  EXPECT_EQ(adrc.values().at("r0"), 150.0);
  EXPECT_EQ(adrc.choices().at("observer"), "zoh");
  EXPECT_FALSE(adrc.values().contains("kp"));
  EXPECT_EQ(adrc.axes().at("y").values().at("b0"), 1.8);
  job::parse_gain_flag("kcp=30,q=20,lead=2", group("ilccc"), axes, spec);
  EXPECT_EQ(spec.gains().at("ilccc").values().at("q_cutoff_hz"), 20.0);
  EXPECT_EQ(spec.gains().at("ilccc").values().at("lead_samples"), 2.0);
  const auto error = [&](const std::string& text, const std::string& name) {
    return error_of([&] { job::parse_gain_flag(text, group(name), axes, spec); });
  };
  EXPECT_NE(error("lead=1.5", "ilccc").find("--ilc lead: expected a whole number"), std::string::npos)
      << error("lead=1.5", "ilccc");
  EXPECT_NE(error("observer=rk4", "adrc").find("euler or zoh"), std::string::npos);
  EXPECT_NE(error("b0=x", "adrc").find("--adrc b0"), std::string::npos) << error("b0=x", "adrc");
  EXPECT_NE(error("z.b0=1", "adrc").find("unknown key 'z.b0'"), std::string::npos) << error("z.b0=1", "adrc");
  EXPECT_NE(error("y.kcp=1", "ilccc").find("--ilc: takes no per-axis values"), std::string::npos)
      << error("y.kcp=1", "ilccc");
  EXPECT_NE(error("w0", "adrc").find("expected KEY=VALUE"), std::string::npos);
  EXPECT_NE(error("w0=1,w0=2", "adrc").find("w0 is given twice"), std::string::npos);
}

TEST(SpecSyntax, GtcfAdrcBandwidths) {
  const std::vector<std::string> axes{"x", "y"};
  netmc::v1::ControllerSpec spec;
  job::parse_gain_flag("wc=250,wo=1200,observer=zoh", group("gtcf_adrc"), axes, spec);
  const auto& gains = spec.gains().at("gtcf_adrc");
  EXPECT_EQ(gains.values().at("wc"), 250.0);
  EXPECT_FALSE(gains.values().contains("wm"));
  EXPECT_EQ(gains.values().at("woc"), 1200.0);  // wo sets both observers
  EXPECT_EQ(gains.values().at("wom"), 1200.0);
  EXPECT_EQ(gains.choices().at("observer"), "zoh");
  job::parse_gain_flag("delay=5", group("gtcf_adrc"), axes, spec);
  EXPECT_EQ(spec.gains().at("gtcf_adrc").values().at("observer_input_delay"), 5.0);
  for (const char* bad : {"wc=0", "wo=1000,wom=500", "kp=3", "observer=rk4", "delay=1.5", "delay=-1"}) {
    EXPECT_NE(error_of([&] { job::parse_gain_flag(bad, group("gtcf_adrc"), axes, spec); }).find("--gtcf-adrc"),
              std::string::npos)
        << bad;
  }
}

TEST(SpecSyntax, TaskSpaceAndInitialPosition) {
  netmc::v1::ControllerSpec spec;
  const std::vector<std::string> axes{"x", "y"};
  job::parse_gain_flag("init_filter=on,wm=2", group("task_space"), axes, spec);
  const auto& gains = spec.gains().at("task_space");
  EXPECT_EQ(gains.choices().at("initialization_filter"), "on");
  EXPECT_FALSE(gains.values().contains("filter_wc"));
  EXPECT_EQ(gains.values().at("filter_wm"), 2.0);
  EXPECT_NE(error_of([&] { job::parse_gain_flag("init_filter=yes", group("task_space"), axes, spec); })
                .find("off or on"),
            std::string::npos);
  EXPECT_NE(error_of([&] { job::parse_gain_flag("wc=-8", group("task_space"), axes, spec); }).find("--task-space"),
            std::string::npos);
  const auto position = parse_position("x=10mm,y=-0.02", "--initial-position");
  EXPECT_DOUBLE_EQ(position.x_m(), 0.01);
  EXPECT_DOUBLE_EQ(position.y_m(), -0.02);
  EXPECT_NE(error_of([&] { parse_position("x=1mm", "--initial-position"); }).find("--initial-position"),
            std::string::npos);
}

}  // namespace
}  // namespace netmc::cli

namespace netmc::cli {
namespace {

TEST(SpecSyntax, PlantOverridesForEveryAxisOrOne) {
  netmc::v1::JobSpec job;
  parse_plant("ballscrew:load_kg=3,y.damping_n_m_s_rad=0.3", job);
  EXPECT_EQ(job.plant(), "ballscrew");
  ASSERT_EQ(job.plant_axes_size(), 2);
  EXPECT_EQ(job.plant_axes(0).axis(), "x");
  ASSERT_EQ(job.plant_axes(0).parameters_size(), 1);
  EXPECT_EQ(job.plant_axes(0).parameters(0).key(), "load_kg");
  EXPECT_EQ(job.plant_axes(0).parameters(0).value(), 3.0);
  ASSERT_EQ(job.plant_axes(1).parameters_size(), 2);  // in the order given
  EXPECT_EQ(job.plant_axes(1).parameters(1).key(), "damping_n_m_s_rad");
  EXPECT_EQ(job.plant_axes(1).parameters(1).value(), 0.3);
  netmc::v1::JobSpec plain;
  parse_plant("linmotor", plain);
  EXPECT_EQ(plain.plant(), "linmotor");
  EXPECT_EQ(plain.plant_axes_size(), 0);
  EXPECT_THROW(parse_plant("ballscrew:w.load_kg=1", plain), std::invalid_argument);
  EXPECT_THROW(parse_plant("ballscrew:load_kg", plain), std::invalid_argument);
  EXPECT_THROW(parse_plant(":load_kg=1", plain), std::invalid_argument);
}

TEST(SpecSyntax, DisturbancePartsOnOneAxis) {
  netmc::v1::JobSpec job;
  parse_disturbance("y:step=0.8,on=2.2s,off=5200ms,sine=0.1,hz=2,noise=0.05,band=50,seed=7", job);
  ASSERT_EQ(job.plant_axes_size(), 1);
  const auto& d = job.plant_axes(0).disturbance();
  EXPECT_EQ(job.plant_axes(0).axis(), "y");
  EXPECT_EQ(d.step().amplitude(), 0.8);
  EXPECT_DOUBLE_EQ(d.step().on_s(), 2.2);
  EXPECT_DOUBLE_EQ(d.step().off_s(), 5.2);
  EXPECT_EQ(d.sine().frequency_hz(), 2.0);
  EXPECT_EQ(d.noise().bandwidth_hz(), 50.0);
  EXPECT_EQ(d.noise().seed(), 7u);
  EXPECT_THROW(parse_disturbance("step=1", job), std::invalid_argument);       // no axis
  EXPECT_THROW(parse_disturbance("x:ramp=1", job), std::invalid_argument);     // unknown part
  EXPECT_THROW(parse_disturbance("x:noise=1,seed=0.5", job), std::invalid_argument);
}

}  // namespace
}  // namespace netmc::cli

#include "client/study_flags.hpp"
#include "server/job/job_builder.hpp"

namespace netmc::cli {
namespace {

// --plant on a preset runs the same experiment on another model: the jobs keep their own plant
// overrides (a set's payload) and the paper's table stays beside them.
TEST(StudyFlags, PlantFlagKeepsThePresetsOverridesAndPaperTable) {
  StudyFlags flags;
  flags.preset = "thesis-darc-sets";
  flags.plant = "linmotor-flex";
  const StudyPlan plan = plan_from_flags(flags);
  EXPECT_FALSE(plan.paper.empty());
  EXPECT_NE(plan.title.find("plant linmotor-flex"), std::string::npos) << plan.title;
  const auto set2 = std::find_if(plan.jobs.begin(), plan.jobs.end(),
                                 [](const auto& job) { return job.name() == "gtcf-darc I Set2"; });
  ASSERT_NE(set2, plan.jobs.end());
  EXPECT_EQ(set2->plant(), "linmotor-flex");
  ASSERT_EQ(set2->plant_axes_size(), 2);
  EXPECT_EQ(set2->plant_axes(1).parameters(0).key(), "load_v_s2_m");
  // A key the new plant lacks is refused when the job is built, naming it.
  flags.plant = "stage004";
  const StudyPlan other = plan_from_flags(flags);
  try {
    job::build_contour_job(other.jobs.at(3));  // gtcf-darc I Set2
    FAIL() << "stage004 took linmotor's payload key";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("stage004 has no parameter 'load_v_s2_m'"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace netmc::cli
