#include "lightcone/frame/output_variable.hpp"

namespace lightcone {
namespace {

constexpr struct {
  Aov aov;
  const char* name;
} kNames[] = {{Aov::kDoppler, "doppler"},       {Aov::kEmissionTime, "emission_time"},
              {Aov::kDistance, "distance"},     {Aov::kObject, "object"},
              {Aov::kDepth, "depth"},           {Aov::kNormal, "normal"},
              {Aov::kImageOrder, "image_order"}};

const char* name_of(Aov aov) {
  for (const auto& n : kNames)
    if (n.aov == aov) return n.name;
  return "";
}

}  // namespace

std::optional<Aov> aov_from_name(std::string_view name) {
  for (const auto& n : kNames)
    if (name == n.name) return n.aov;
  return std::nullopt;
}

std::string aov_name(Aov aov) {
  return name_of(aov);
}

std::string aov_map_label(Aov aov) {
  switch (aov) {
    case Aov::kDoppler:
      return "Doppler factor D";
    case Aov::kEmissionTime:
      return "emission time (scene units)";
    case Aov::kDistance:
      return "distance (scene units)";
    case Aov::kObject:
      return "object index";
    case Aov::kDepth:
      return "depth (scene units)";
    case Aov::kNormal:
      return "normal";
    case Aov::kImageOrder:
      return "image order";
  }
  return name_of(aov);
}

std::vector<std::string> aov_channel_names(Aov aov) {
  const std::string name = name_of(aov);
  if (aov == Aov::kNormal) return {name + ".X", name + ".Y", name + ".Z"};
  return {name};
}

bool aov_needs_world_time(Aov aov) {
  return aov == Aov::kEmissionTime || aov == Aov::kDistance || aov == Aov::kDepth;
}

}  // namespace lightcone
