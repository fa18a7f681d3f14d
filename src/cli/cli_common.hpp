// What the commands share: loading a scene with its warnings, checking output targets, the
// interrupt flag and the exit statuses.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

constexpr int kBadInput = 2;
constexpr int kInterrupted = 130;  // 128 + SIGINT, as shells report it

// Set by the SIGINT handler on_interrupt while a render runs.
extern std::atomic<bool> interrupted;
extern "C" void on_interrupt(int);

// Loads a scene file with --set overrides, printing its warnings (and the tangent
// approximation's) to stderr. Throws InputError.
Scene load(const std::string& file, const std::vector<std::string>& overrides);

// Checked before rendering: the target is a regular file or absent, and its folder exists and
// is writable (InputError naming `option` otherwise).
void require_writable_target(const std::string& option, const std::string& path);

// Whether two paths name the same file.
bool same_file(const std::string& a, const std::string& b);

RasterTessellation tessellation_mode(const std::string& name);

}  // namespace lightcone
