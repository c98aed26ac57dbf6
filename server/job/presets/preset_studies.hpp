#pragma once
// The studies behind the named presets, one builder a preset, grouped by source (the sources'
// short names: docs/references.md). Only presets.cpp's registration table names them.

#include "server/job/presets/presets.hpp"

namespace netmc::presets {

// Paper 001 (presets_paper001.cpp).
StudyPlan seed001();
StudyPlan seed001_ellipse();
StudyPlan seed001_line();
StudyPlan seed001_long_delay();
StudyPlan seed001_bursty();

// The thesis (presets_thesis.cpp).
StudyPlan thesis_ellipse();
StudyPlan thesis_circle();
StudyPlan thesis_darc();
StudyPlan thesis_darc_sets();
StudyPlan thesis_cogging();
StudyPlan thesis_ellipse_delay();
StudyPlan thesis_spatial();
StudyPlan thesis_dead_zone();

// Paper 004 (presets_paper004.cpp).
StudyPlan seed004();

// Paper 002 (presets_paper002.cpp).
StudyPlan seed002();

}  // namespace netmc::presets
