// Steps per second of the swarmvm C++ VM and of the baseline (cpp_baseline.hpp) on the host.
//
//   cpp_steps STEPS IMAGE...    prints "IMAGE VM_STEPS_PER_S BASELINE_STEPS_PER_S" per image
//
// Both VMs run the same pseudo-random event script (a quarter of the uncontrollable checks
// true per step) with the same seed; their state sequences are compared first, so the timing
// compares the same work. Each figure is the best of 5 alternating rounds of STEPS steps.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cpp_baseline.hpp"
#include "swarmvm.hpp"

namespace {

constexpr std::size_t kRows = 4096;
constexpr int kRounds = 5;

std::vector<swarmvm::Mask> make_script(const swarmvm::Image& image) {
    swarmvm::XorShift32 rng(12345);
    std::vector<swarmvm::Mask> rows(kRows);
    for (swarmvm::Mask& row : rows) {
        for (unsigned e = 0; e < image.num_events; ++e) {
            if (!image.controllable.test(e) && (rng.next() >> 30) == 0) row.set(e);
        }
    }
    return rows;
}

template <class Step>
double steps_per_second(std::size_t steps, Step&& step) {
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < steps; ++i) step(i);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    return static_cast<double>(steps) / elapsed.count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s STEPS IMAGE...\n", argv[0]);
        return 2;
    }
    const std::size_t steps = std::stoul(argv[1]);
    for (int a = 2; a < argc; ++a) {
        const swarmvm::Image image = swarmvm::Image::load(argv[a]);
        const std::vector<swarmvm::Mask> rows = make_script(image);
        std::size_t current = 0;
        swarmvm::VM vm(image);
        baseline::FlatVM flat(image, 1);
        for (unsigned e = 0; e < image.num_events; ++e) {
            if (image.controllable.test(e)) continue;
            vm.set_check(e, [&rows, &current, e](void*) { return rows[current % kRows].test(e); });
            flat.add_check(image.event_name(e), [&rows, &current, e](void*) {
                return static_cast<unsigned char>(rows[current % kRows].test(e));
            });
        }
        for (current = 0; current < kRows; ++current) {
            vm.step();
            flat.run_step();
            for (std::size_t s = 0; s < vm.states().size(); ++s) {
                if (vm.states()[s] != flat.states()[s]) {
                    std::fprintf(stderr, "%s: baseline and swarmvm disagree at step %zu\n", argv[a], current + 1);
                    return 1;
                }
            }
        }
        // Best of alternating rounds: the host is shared, so load spikes hit single rounds.
        double fast = 0, slow = 0;
        for (int round = 0; round < kRounds; ++round) {
            fast = std::max(fast, steps_per_second(steps, [&](std::size_t i) { current = i; vm.step(); }));
            slow = std::max(slow, steps_per_second(steps, [&](std::size_t i) { current = i; flat.run_step(); }));
        }
        std::printf("%s %.0f %.0f\n", argv[a], fast, slow);
    }
    return 0;
}
