// How a speed is printed wherever a user reads one (info, the viewer's overlay): a speed below c
// never reads as c.
#pragma once

#include <string>

namespace lightcone {

// `beta` (a speed in units of c) with at least `digits` significant digits, and more where fewer
// would round a speed below 1 up to 1: 0.99999998 for 1 - 1.85e-8, not 1. At most 17, which
// tells every double below 1 from 1.
std::string speed_text(double beta, int digits = 6);

}  // namespace lightcone
