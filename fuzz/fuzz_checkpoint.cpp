// libFuzzer target: the checkpoint decoder (and the run state inside it), then a few steps of
// the restored world. A file that does not start with the checkpoint magic is taken as a
// payload and sealed with the right header and checksum first, so the fuzzer explores what
// lies behind the checksum rather than the checksum itself. IoError is the expected answer to
// a bad file and NumericalError to a state that cannot be stepped; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "runout/checkpoint.hpp"
#include "runout/errors.hpp"
#include "runout/io/files.hpp"
#include "runout/io/scene_file.hpp"
#include "runout/run.hpp"
#include "runout/setup.hpp"

namespace {

struct Fixture {
  runout::SceneDef scene = runout::io::read_scene_file(RUNOUT_FUZZ_SCENE);
  runout::SceneSetup setup = runout::derive_setup(scene, RUNOUT_FUZZ_SCENE);
  runout::World world = runout::build_explicit_world(scene, setup, 1);
  std::uint64_t key = runout::io::physics_key(scene);
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const Fixture fixture;
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (bytes.rfind("RUNOUTCK", 0) != 0) bytes = runout::seal_checkpoint(bytes);
  runout::World world = fixture.world;
  try {
    const std::string state = runout::decode_checkpoint(bytes, fixture.key, world, "fuzz.ckpt");
    runout::RunState run = runout::decode_run_state(state, "fuzz.ckpt");
    (void)run;
    for (int s = 0; s < 20; ++s) world.step();
    world.check_escape(0.0);
  } catch (const runout::IoError&) {
  } catch (const runout::NumericalError&) {
  }
  return 0;
}
