#include "server/job/reference_limits.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace netmc::job {
namespace {

// One refusal: the field, the range, the value.
[[noreturn]] void refuse(const std::string& field, const std::string& expected, double value) {
  throw std::invalid_argument("trajectory." + field + ": expected " + expected + ", got " + fmt::format("{:g}", value));
}

void in_range(double value, double low, double high, const std::string& field, const std::string& unit) {
  if (!(value >= low && value <= high)) {
    refuse(field, fmt::format("a number in [{:g}, {:g}]{}", low, high, unit), value);
  }
}

class ReferenceChecker {
 public:
  explicit ReferenceChecker(double sample_period_s) : sample_period_s_(sample_period_s) {}

  void coordinate(double value, const std::string& field) const {
    in_range(value, -kWorkspaceM, kWorkspaceM, field, " m (the workspace)");
  }
  void length(double value, const std::string& field) const {
    in_range(value, kMinContourLengthM, kWorkspaceM, field, " m");
  }
  void amplitude(double value, const std::string& field) const { in_range(value, 0.0, kWorkspaceM, field, " m"); }
  void angle(double value, const std::string& field) const {
    in_range(value, -kMaxAngleRad, kMaxAngleRad, field, " rad");
  }
  // A period or a motion's duration: finite, at least kMinSamplesPerPeriod samples, at most kMaxPeriodS.
  void period(double value, const std::string& field) const {
    const double shortest = kMinSamplesPerPeriod * sample_period_s_;
    if (!(value > 0.0 && value >= shortest && value <= kMaxPeriodS)) {
      refuse(field,
             shortest > 0.0 ? fmt::format("a number in [{:g}, {:g}] s ({:g} sample periods of {:g} s or more)", shortest,
                                          kMaxPeriodS, kMinSamplesPerPeriod, sample_period_s_)
                            : fmt::format("a number in (0, {:g}] s", kMaxPeriodS),
             value);
    }
  }
  // 0 (one revolution, or as the message says) or a positive count.
  void revolutions(double value, const std::string& field) const {
    in_range(value, 0.0, kMaxRevolutions, field, " (0: the default)");
  }
  void frequency(double value, const std::string& field) const {
    const double highest = sample_period_s_ > 0.0 ? 1.0 / (kMinSamplesPerPeriod * sample_period_s_) : 1e6;
    in_range(value, 0.0, highest, field, sample_period_s_ > 0.0 ? " Hz (10 samples per cycle or more)" : " Hz");
  }
  // A speed or an acceleration: in [least, most], or 0 where 0 means none.
  void rate(double value, double least, double most, const std::string& field, const std::string& unit,
            bool zero_allowed) const {
    if (zero_allowed && value == 0.0) return;
    if (!(value >= least && value <= most)) {
      refuse(field, fmt::format("{}a number in [{:g}, {:g}] {}", zero_allowed ? "0 or " : "", least, most, unit), value);
    }
  }
  void speed(double value, const std::string& field, bool zero_allowed) const {
    rate(value, kMinSpeedMS, kMaxSpeedMS, field, "m/s", zero_allowed);
  }
  void acceleration(double value, const std::string& field, bool zero_allowed) const {
    rate(value, kMinSpeedMS, kMaxAccelerationMS2, field, "m/s^2", zero_allowed);
  }
  void feed(const netmc::v1::FeedRate& f, const std::string& field) const {
    speed(f.feed_m_s(), field + ".feed_m_s", false);
    acceleration(f.max_normal_acceleration_m_s2(), field + ".max_normal_acceleration_m_s2", false);
    acceleration(f.max_tangential_acceleration_m_s2(), field + ".max_tangential_acceleration_m_s2", true);
  }
  void points(const google::protobuf::RepeatedPtrField<netmc::v1::Point2>& points, const std::string& field) const {
    for (int i = 0; i < points.size(); ++i) {
      const std::string point = field + ".points[" + std::to_string(i) + "]";
      coordinate(points[i].x_m(), point + ".x_m");
      coordinate(points[i].y_m(), point + ".y_m");
    }
  }
  // A direction in space: finite components of at most 1e3, not all (nearly) zero.
  void direction(double x, double y, double z, const std::string& field) const {
    for (const auto& [value, axis] : {std::pair{x, "x"}, std::pair{y, "y"}, std::pair{z, "z"}}) {
      in_range(value, -1e3, 1e3, field + "_" + axis, "");
    }
    if (!(std::sqrt(x * x + y * y + z * z) >= 1e-6)) {
      refuse(field, "a direction of length 1e-6 or more", std::sqrt(x * x + y * y + z * z));
    }
  }

 private:
  double sample_period_s_;
};

}  // namespace

void check_reference_limits(const netmc::v1::Trajectory& t, double sample_period_s) {
  const ReferenceChecker check(sample_period_s);
  if (t.has_halt()) {
    in_range(t.halt().at_s(), 0.0, kMaxPeriodS, "halt.at_s", " s");
    in_range(t.halt().duration_s(), 0.0, kMaxPeriodS, "halt.duration_s", " s");
  }
  switch (t.shape_case()) {
    case netmc::v1::Trajectory::kCircle: {
      const auto& c = t.circle();
      check.coordinate(c.center_x_m(), "circle.center_x_m");
      check.coordinate(c.center_y_m(), "circle.center_y_m");
      check.length(c.radius_m(), "circle.radius_m");
      check.period(c.period_s(), "circle.period_s");
      check.angle(c.start_angle_rad(), "circle.start_angle_rad");
      check.revolutions(c.revolutions(), "circle.revolutions");
      in_range(c.ramp_s(), 0.0, kMaxPeriodS, "circle.ramp_s", " s");
      break;
    }
    case netmc::v1::Trajectory::kEllipse: {
      const auto& e = t.ellipse();
      check.coordinate(e.center_x_m(), "ellipse.center_x_m");
      check.coordinate(e.center_y_m(), "ellipse.center_y_m");
      check.length(e.semi_axis_x_m(), "ellipse.semi_axis_x_m");
      check.length(e.semi_axis_y_m(), "ellipse.semi_axis_y_m");
      check.angle(e.start_angle_rad(), "ellipse.start_angle_rad");
      check.revolutions(e.revolutions(), "ellipse.revolutions");
      if (e.has_feed()) {
        check.feed(e.feed(), "ellipse.feed");
      } else {
        check.period(e.period_s(), "ellipse.period_s");
      }
      break;
    }
    case netmc::v1::Trajectory::kLine: {
      const auto& l = t.line();
      check.coordinate(l.x0_m(), "line.x0_m");
      check.coordinate(l.y0_m(), "line.y0_m");
      check.coordinate(l.x1_m(), "line.x1_m");
      check.coordinate(l.y1_m(), "line.y1_m");
      check.period(l.duration_s(), "line.duration_s");
      break;
    }
    case netmc::v1::Trajectory::kLissajous: {
      const auto& l = t.lissajous();
      check.coordinate(l.center_x_m(), "lissajous.center_x_m");
      check.coordinate(l.center_y_m(), "lissajous.center_y_m");
      check.amplitude(l.amplitude_x_m(), "lissajous.amplitude_x_m");
      check.amplitude(l.amplitude_y_m(), "lissajous.amplitude_y_m");
      check.angle(l.phase_rad(), "lissajous.phase_rad");
      if (l.has_feed()) {
        check.feed(l.feed(), "lissajous.feed");
      } else {
        check.period(l.period_s(), "lissajous.period_s");
      }
      break;
    }
    case netmc::v1::Trajectory::kPolyline: {
      const auto& l = t.polyline();
      check.points(l.points(), "polyline");
      check.speed(l.max_speed_m_s(), "polyline.max_speed_m_s", false);
      check.acceleration(l.max_acceleration_m_s2(), "polyline.max_acceleration_m_s2", false);
      check.speed(l.corner_speed_m_s(), "polyline.corner_speed_m_s", true);
      check.rate(l.max_jerk_m_s3(), kMinSpeedMS, kMaxJerkMS3, "polyline.max_jerk_m_s3", "m/s^3", true);
      break;
    }
    case netmc::v1::Trajectory::kSpline:
      check.points(t.spline().points(), "spline");
      check.feed(t.spline().feed(), "spline.feed");
      break;
    case netmc::v1::Trajectory::kHeart: {
      const auto& h = t.heart();
      check.coordinate(h.center_x_m(), "heart.center_x_m");
      check.coordinate(h.center_y_m(), "heart.center_y_m");
      // The heart is 32 scales wide: its scale keeps it within the workspace's size.
      in_range(h.scale_m(), kMinContourLengthM, kWorkspaceM / 16.0, "heart.scale_m", " m");
      check.period(h.period_s(), "heart.period_s");
      break;
    }
    case netmc::v1::Trajectory::kSpatialCircle: {
      const auto& c = t.spatial_circle();
      check.coordinate(c.center_x_m(), "spatial_circle.center_x_m");
      check.coordinate(c.center_y_m(), "spatial_circle.center_y_m");
      check.coordinate(c.center_z_m(), "spatial_circle.center_z_m");
      check.length(c.radius_m(), "spatial_circle.radius_m");
      check.direction(c.normal_x(), c.normal_y(), c.normal_z(), "spatial_circle.normal");
      check.direction(c.start_x(), c.start_y(), c.start_z(), "spatial_circle.start");
      check.period(c.period_s(), "spatial_circle.period_s");
      check.revolutions(c.revolutions(), "spatial_circle.revolutions");
      break;
    }
    case netmc::v1::Trajectory::kMultiSine: {
      const auto& m = t.multi_sine();
      check.coordinate(m.offset_m(), "multi_sine.offset_m");
      for (int i = 0; i < m.terms_size(); ++i) {
        const std::string term = "multi_sine.terms[" + std::to_string(i) + "]";
        check.amplitude(m.terms(i).amplitude_m(), term + ".amplitude_m");
        check.frequency(m.terms(i).frequency_hz(), term + ".frequency_hz");
        check.angle(m.terms(i).phase_rad(), term + ".phase_rad");
      }
      check.period(m.duration_s(), "multi_sine.duration_s");
      if (m.period_s() != 0.0) check.period(m.period_s(), "multi_sine.period_s");
      break;
    }
    case netmc::v1::Trajectory::SHAPE_NOT_SET:
      break;  // the builder says what is missing
  }
}

}  // namespace netmc::job
