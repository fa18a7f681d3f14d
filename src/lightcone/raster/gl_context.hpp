// An OpenGL 3.3 core context without a window, through EGL: the driver's on a machine with a
// GPU, Mesa's llvmpipe without one.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace lightcone {

// No OpenGL 3.3 core context can be had (no display, no driver, too old a driver).
class GlUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class HeadlessGlContext {
 public:
  // Creates the context and makes it current on this thread. Throws GlUnavailable when no EGL
  // display or no OpenGL 3.3 core context can be had.
  HeadlessGlContext();
  ~HeadlessGlContext();
  HeadlessGlContext(const HeadlessGlContext&) = delete;
  HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

  // "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)" and the like.
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lightcone
