// An image loaded during a step (docs/semantics.md, "Reset and swap"), for
// tests/cpp/test_swap_mid_step_cpp.py, which runs the same script on the Python VM: EV_x's
// action loads the second image the first time it fires, while EV_y fires too. Prints, per
// step, the events fired (indices, of the image the step began on), the states and the
// violations; then what a violation hook that loads gets, and whether an action may load
// twice (the action running is one of those the loads replace: built with AddressSanitizer,
// a use after free would stop the program).
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "swarmvm.hpp"

namespace {

using swarmvm::VM;

void print_step(const std::vector<unsigned>& fired, const VM& vm) {
    std::string line = "step fired=";
    for (std::size_t i = 0; i < fired.size(); ++i) line += (i ? "," : "") + std::to_string(fired[i]);
    line += " states=";
    for (std::size_t s = 0; s < vm.states().size(); ++s) line += (s ? "," : "") + std::to_string(vm.states()[s]);
    std::printf("%s violations=%u\n", line.c_str(), static_cast<unsigned>(vm.violations()));
}

void load_in_action(const swarmvm::Image& first, const swarmvm::Image& second, unsigned steps) {
    VM vm(first);
    bool loaded = false;
    const std::string tag = "twice";
    vm.set_check("EV_x", [](void*) { return true; });
    vm.set_check("EV_y", [](void*) { return true; });
    vm.bind("EV_x", [&vm, &loaded, &second, tag](void*) {
        if (loaded) return;
        loaded = true;
        vm.load(second);
        vm.load(second);                                 // the running action is replaced twice
        if (tag != "twice") std::printf("capture lost\n");   // and its captures still live
    });
    for (unsigned i = 0; i < steps; ++i) print_step(vm.step(), vm);
}

void load_in_violation_hook(const swarmvm::Image& first, const swarmvm::Image& second) {
    VM vm(second);      // in its initial state EV_y has no move: a violation
    vm.set_check("EV_y", [](void*) { return true; });
    vm.on_violation([&vm, &first](unsigned, unsigned) { vm.load(first); });
    try {
        vm.step();
        std::printf("hook no-throw\n");
    } catch (const swarmvm::CallbackError& error) {     // nesting the load's std::logic_error
        try {
            std::rethrow_if_nested(error);
        } catch (const std::logic_error& cause) {
            std::printf("hook %s: %s\n", error.kind().c_str(), cause.what());
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: swap_mid_step FIRST.svm SECOND.svm\n");
        return 2;
    }
    const swarmvm::Image first = swarmvm::Image::load(argv[1]), second = swarmvm::Image::load(argv[2]);
    load_in_action(first, second, 6);
    load_in_violation_hook(first, second);
    return 0;
}
