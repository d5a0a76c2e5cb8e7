// Conformance harness of the C++ VM (docs/conformance.md): runs a batch of event scripts and
// option combinations on one table image and prints the canonical trace of each run.
//
//   conformance_harness --image FILE RUNS      image loaded from a .svm file at run time
//   conformance_harness --compiled K RUNS      image K of those compiled in (SWARMVM_IMAGES)
//
// Build with -DSWARMVM_IMAGES='"images.inc"' to compile images in; the file defines
// kImages[] (byte arrays) and kImageSizes[]. Both modes go through Image::parse.
//
// RUNS is text: "scripts K", then K scripts each "script STEPS" followed by STEPS rows (event
// indices separated by spaces, or "-"); then "runs R" and R lines
// "INPUTS CONTROL POLICY SEED SCRIPT". Each run's trace is followed by a line "end".
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "swarmvm.hpp"

#ifdef SWARMVM_IMAGES
#include SWARMVM_IMAGES
#endif

namespace {

struct Run {
    swarmvm::Options options;
    std::size_t script = 0;
};

std::vector<swarmvm::Mask> read_script(std::istream& in) {
    std::string word;
    std::size_t steps = 0;
    in >> word >> steps;
    if (word != "script") throw std::runtime_error("runs file: expected 'script', got '" + word + "'");
    std::string line;
    std::getline(in, line);
    std::vector<swarmvm::Mask> rows;
    for (std::size_t i = 0; i < steps; ++i) {
        std::getline(in, line);
        swarmvm::Mask row;
        std::istringstream tokens(line);
        std::string token;
        while (tokens >> token) {
            if (token != "-") row.set(static_cast<unsigned>(std::stoul(token)));
        }
        rows.push_back(row);
    }
    return rows;
}

swarmvm::Image image_from(const std::string& mode, const std::string& what) {
    if (mode == "--image") return swarmvm::Image::load(what);
#ifdef SWARMVM_IMAGES
    if (mode == "--compiled") {
        const std::size_t k = std::stoul(what);
        if (k >= sizeof kImageSizes / sizeof kImageSizes[0]) throw std::runtime_error("no compiled-in image " + what);
        return swarmvm::Image::parse(kImages[k], kImageSizes[k]);
    }
#endif
    throw std::runtime_error("unknown image source " + mode);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::cerr << "usage: " << argv[0] << " --image FILE|--compiled K RUNS\n";
        return 2;
    }
    try {
        swarmvm::Image image = image_from(argv[1], argv[2]);
        std::ifstream in(argv[3]);
        if (!in) throw std::runtime_error(std::string("cannot read ") + argv[3]);
        std::string word;
        std::size_t count = 0;
        in >> word >> count;
        std::vector<std::vector<swarmvm::Mask>> scripts;
        for (std::size_t i = 0; i < count; ++i) scripts.push_back(read_script(in));
        in >> word >> count;
        std::vector<Run> runs;
        for (std::size_t i = 0; i < count; ++i) {
            std::string inputs, control, policy;
            unsigned long seed = 0;
            Run run;
            in >> inputs >> control >> policy >> seed >> run.script;
            run.options.inputs = swarmvm::parse_inputs(inputs);
            run.options.control = swarmvm::parse_control(control);
            run.options.policy = swarmvm::parse_policy(policy);
            run.options.seed = static_cast<std::uint32_t>(seed);
            runs.push_back(run);
        }
        std::string out;
        for (const Run& run : runs) {
            swarmvm::VM vm(image, run.options);
            for (const std::string& line : swarmvm::replay(vm, scripts.at(run.script))) out += line + "\n";
            out += "end\n";
        }
        std::cout << out;
    } catch (const std::exception& ex) {
        std::cerr << "conformance_harness: " << ex.what() << "\n";
        return 1;
    }
    return 0;
}
