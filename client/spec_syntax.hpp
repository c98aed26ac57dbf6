#pragma once
// The compact flag syntax of the CLI: `kind:key=value,...` with unit-suffixed quantities
// (SI unless a suffix s, ms, us, m, mm, um is given). Errors are std::invalid_argument naming
// the flag and the expected form.

#include <string>
#include <string_view>
#include <vector>

#include "idl/job.pb.h"
#include "server/job/quantity_text.hpp"

namespace netmc::cli {

// Quantities and key lists: server/job/quantity_text.hpp.
using job::parse_quantity;
using job::Quantity;
using job::split_list;

// --trajectory circle:r=10mm,cx=50mm,cy=50mm,period=8s | ellipse:a=..,b=..,cx=..,cy=..,period=..
//              (ellipse and lissajous: feed=..,amax=..[,at=..] instead of period for a feed rate)
//              | line:x0=..,y0=..,x1=..,y1=..,duration=..
//              | lissajous:ax=..,ay=..,p=3,q=2,period=..[,phase=..,cx=..,cy=..][,feed=..,amax=..[,at=..]]
//              | polyline:points=X,Y;X,Y;...,vmax=..,amax=..[,corner=..]
//              | spline:points=X,Y;X,Y;...,feed=..,amax=..[,at=..]
// Points are x,y pairs of lengths separated by ';' (closed when the last equals the first).
netmc::v1::Trajectory parse_trajectory(std::string_view text);
// --delay none | constant:1ms | uniform:min=0.3ms,max=0.8ms | normal:mean=..,sd=..[,min=..,max=..]
//         | pareto:scale=..,shape=..[,max=..] | markov:good=0.3ms..0.8ms,bad=5ms..10ms,p_gb=..,p_bg=..
//         | trace:FILE.csv
netmc::v1::DelayProfile parse_delay(std::string_view text, std::string_view flag);
// --loss none | bernoulli:p=0.01 | gilbert:p_gb=..,p_bg=..[,good=..,bad=..]
netmc::v1::LossProfile parse_loss(std::string_view text, std::string_view flag);
// Controller gains: one flag per gains group of the controller registry
// (server/job/controller_gains.hpp, parse_gain_flag).
// --initial-position x=..,y=.. (lengths)
netmc::v1::Position parse_position(std::string_view text, std::string_view flag);
// --plant NAME[:[AXIS.]KEY=VALUE,...]: the plant, and parameter overrides for every axis of `job`
// (KEY=VALUE) or for one (AXIS.KEY=VALUE), appended to job.plant_axes in order.
void parse_plant(std::string_view text, netmc::v1::JobSpec& job);
// --disturbance AXIS:constant=..,step=..,on=..,off=..,sine=..,hz=..,phase=..,noise=..,band=..,seed=..
// (amplitudes in the plant's input unit): the disturbance of one axis of `job`.
void parse_disturbance(std::string_view text, netmc::v1::JobSpec& job);
// --dead-zone-inverse AXIS:b_r=..,b_l=..[,m_r=..,m_l=..] (volts; slopes 1 when omitted): a fixed
// dead-zone inverse (thesis eq. 5-4) between the controller and that axis of `job`.
void parse_dead_zone_inverse(std::string_view text, netmc::v1::JobSpec& job);

}  // namespace netmc::cli
