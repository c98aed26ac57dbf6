#pragma once
// Spec files of netmc 0.1 carried a typed message per controller family in ControllerSpec
// (adrc, adrc_y, pid, ilccc, task_space, ffpid_x, ...). They are read still: their controller's
// gains are rewritten into ControllerSpec.gains (by group, an axis's own under axes) before the
// spec is checked, so an old file runs as it always did.

#include <string>

namespace netmc::job {

// The JSON text with its legacy controller fields, in snake_case or camelCase, moved into
// "gains". Text that is not a JSON object, or has none of them, comes back as it was (the
// checks that follow name what is wrong with it).
std::string upgrade_legacy_spec_json(const std::string& text);

}  // namespace netmc::job
