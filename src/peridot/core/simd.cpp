#include "peridot/core/simd.hpp"

#include <hwy/highway.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

namespace peridot::simd {

namespace {

/// Peridot's name of a Highway target: lower case, and AVX3 (AVX-512 F, VL, DQ, BW) as "avx512".
std::string target_name(std::int64_t target) {
  if (target == HWY_AVX3) return "avx512";
  std::string name = hwy::TargetName(target);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

struct Target {
  std::string name;
  std::int64_t bit;
};

/// The compiled targets this CPU supports, best first (Highway's bits rise as targets get worse), read
/// before anything is forced.
const std::vector<Target>& hardware_targets() {
  static const std::vector<Target> targets = [] {
    std::vector<Target> list;
    for (std::int64_t bit : hwy::SupportedAndGeneratedTargets()) list.push_back({target_name(bit), bit});
    std::sort(list.begin(), list.end(), [](const Target& a, const Target& b) { return a.bit < b.bit; });
    return list;
  }();
  return targets;
}

std::once_flag environment_read;

}  // namespace

const std::vector<std::string>& available_targets() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const Target& t : hardware_targets()) list.push_back(t.name);
    return list;
  }();
  return names;
}

std::string active_target() {
  apply_environment();
  const std::int64_t usable = hwy::SupportedTargets() & HWY_TARGETS;
  return usable ? target_name(usable & -usable) : std::string("none");  // the lowest bit: the best
}

void force_target(const std::string& name) {
  hardware_targets();  // the list of what the CPU offers is taken before any target is forced
  if (name.empty()) {
    hwy::SetSupportedTargetsForTest(0);
    return;
  }
  for (const Target& t : hardware_targets())
    if (t.name == name) {
      hwy::SetSupportedTargetsForTest(t.bit);
      return;
    }
  std::string offered;
  for (const std::string& n : available_targets()) offered += (offered.empty() ? "" : ", ") + n;
  throw std::invalid_argument("SIMD target '" + name + "' is not available on this CPU (this build and CPU offer: " +
                              offered + ")");
}

void apply_environment() {
  std::call_once(environment_read, [] {
    if (const char* value = std::getenv("PERIDOT_SIMD"); value && *value) {
      try {
        force_target(value);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("PERIDOT_SIMD: ") + e.what());
      }
    }
  });
}

std::string describe() {
  std::string offered;
  for (const std::string& n : available_targets()) offered += (offered.empty() ? "" : ", ") + n;
  return active_target() + " (available: " + offered + "; PERIDOT_SIMD forces one)";
}

}  // namespace peridot::simd
