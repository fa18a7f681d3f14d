#include "viewer/probe_readouts.hpp"

#include <fmt/format.h>

#include <cstdio>

#include "lightcone/frame/request_rules.hpp"
#include "lightcone/io/locate_json.hpp"

namespace lightcone {
void ProbeReadouts::click(const Scene& frame, double x, double y) {
  if (!source_) return;
  if (pending_.valid()) return;  // one at a time: the next click waits for this one
  if (done_.size() >= kMaxProbes) clear();
  refused_.reset();
  if (const auto refused = probe_refused(frame, x, y)) {
    refused_ = *refused;
    std::fprintf(stderr, "lightcone: %s\n", refused->c_str());
    return;
  }
  pending_mark_ = Mark{x, y};
  pending_ = std::async(std::launch::async, [source = source_, frame, x, y] {
    const PixelProbe probe = source(frame, x, y);
    return Done{probe, probe_json(probe, frame)};
  });
}

void ProbeReadouts::clear() {
  done_.clear();
  lines_.clear();
  refused_.reset();
}

void ProbeReadouts::poll(const Scene& frame) {
  if (!pending_.valid() || pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return;
  Done done = pending_.get();
  pending_mark_.reset();
  std::printf("%s\n", done.json.c_str());
  std::fflush(stdout);
  done_.push_back(std::move(done));
  std::vector<PixelProbe> probes;
  for (const Done& d : done_) probes.push_back(d.probe);
  lines_ = probe_lines(probes, frame);
}

std::vector<std::string> ProbeReadouts::lines() const {
  std::vector<std::string> out = lines_;
  if (pending_.valid()) out.push_back(fmt::format("{}: ...", done_.size() + 1));
  if (refused_) out.push_back(*refused_);
  return out;
}

std::vector<ProbeReadouts::Mark> ProbeReadouts::marks() const {
  std::vector<Mark> out;
  for (const Done& d : done_) out.push_back({d.probe.pixel_x, d.probe.pixel_y});
  if (pending_mark_) out.push_back(*pending_mark_);
  return out;
}

}  // namespace lightcone
