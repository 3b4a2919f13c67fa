// libFuzzer target for the AMC (Acclaim motion) reader: the input bytes are taken as the text
// of an .amc file and given to mg::parse_amc with the channel layout of a fixed skeleton;
// when that succeeds, the frames are turned into motion with mg::motion_from_amc.
//
// The skeleton is read once, in LLVMFuzzerInitialize, from the ASF file named by the
// environment variable MOTIONGRAPH_FUZZ_ASF (scripts/fuzz.sh sets it to the bundled
// data/cmu/16/16.asf, the skeleton of the seed corpus). Without the variable, the small ASF
// below is used. A skeleton that cannot be read or built stops the fuzzer at start-up.
// Errors are expected results; the fuzzer looks for crashes, hangs, leaks and sanitizer
// reports. Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

#include "motiongraph/io/amc_parser.h"
#include "motiongraph/io/asf_parser.h"
#include "motiongraph/io/file.h"
#include "motiongraph/motion/acclaim_import.h"

namespace {

// A root with all six channels and a three-bone leg, bone names as in the CMU skeletons.
constexpr std::string_view kFallbackAsf = R"(:version 1.10
:name fuzz
:units
  mass 1.0
  length 0.45
  angle deg
:root
  order TX TY TZ RX RY RZ
  axis XYZ
  position 0 0 0
  orientation 0 0 0
:bonedata
  begin
    id 1
    name lhipjoint
    direction 0.635348 -0.713158 0.296208
    length 2.47672
    axis 0 0 0 XYZ
  end
  begin
    id 2
    name lfemur
    direction 0.34202 -0.939693 0
    length 7.03469
    axis 0 0 20 XYZ
    dof rx ry rz
    limits (-160.0 20.0)
           (-70.0 70.0)
           (-60.0 70.0)
  end
  begin
    id 3
    name ltibia
    direction 0.34202 -0.939693 0
    length 7.78223
    axis 0 0 20 XYZ
    dof rx
    limits (-10.0 170.0)
  end
:hierarchy
  begin
    root lhipjoint
    lhipjoint lfemur
    lfemur ltibia
  end
)";

constexpr double kFps = 120.0;  // the CMU capture rate; AMC files do not store one

std::optional<mg::AcclaimRig> g_rig;

[[noreturn]] void die(const std::string& message) {
  std::fprintf(stderr, "fuzz_amc: %s\n", message.c_str());
  std::exit(1);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  std::string text(kFallbackAsf);
  std::string name = "<built-in fuzz ASF>";
  if (const char* path = std::getenv("MOTIONGRAPH_FUZZ_ASF"); path != nullptr && *path != '\0') {
    auto file = mg::read_text_file(path);
    if (!file.ok()) die("MOTIONGRAPH_FUZZ_ASF: " + file.error().to_string());
    text = std::move(file.value());
    name = path;
  }
  auto asf = mg::parse_asf(text, name);
  if (!asf.ok()) die(asf.error().to_string());
  auto rig = mg::build_acclaim_rig(asf.value());
  if (!rig.ok()) die(rig.error().to_string());
  g_rig = std::move(rig.value());
  std::fprintf(stderr, "fuzz_amc: skeleton %s, %zu AMC lines, %d values per frame\n", name.c_str(),
               g_rig->amc_layout.bone_names.size(), g_rig->amc_layout.values_per_frame());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto amc = mg::parse_amc(text, "fuzz.amc", g_rig->amc_layout, g_rig->angles_in_degrees);
  if (!amc.ok()) return 0;
  const mg::Motion motion = mg::motion_from_amc(*g_rig, amc.value(), kFps);
  (void)motion;
  return 0;
}
