// The C++ runtime's input layer under test (tests/boundary/test_runtime_loaders.py): every path
// the runtime loads goes through swarmvm::read_regular_file, which refuses FIFOs, devices and
// folders without waiting on them. Usage, one line out per path:
//   runtime_loader image PATH...    Image::load          "ok EVENTS" or "refused: MESSAGE"
//   runtime_loader beside PATH...   load_beside (SCT)    "ok EVENTS" or "refused: MESSAGE"
#include <cstdio>
#include <stdexcept>
#include <string>

#include "swarmvm.hpp"

int main(int argc, char** argv) {
    if (argc < 2) return 2;
    const std::string verb = argv[1];
    for (int i = 2; i < argc; ++i) {
        try {
            const swarmvm::Image image = verb == "image" ? swarmvm::Image::load(argv[i]) : swarmvm::load_beside(argv[i]);
            std::printf("ok %u\n", static_cast<unsigned>(image.num_events));
        } catch (const std::runtime_error& error) {
            std::printf("refused: %s\n", error.what());
        }
    }
    return 0;
}
