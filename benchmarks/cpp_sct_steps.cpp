// Steps per second of an SCT through the published C++ API only, for benchmarks/cpp_steps.py:
// built once against the published sct.cpp (the OpenSwarm VM, with yaml-cpp and ARGoS) and
// once against swarmvm's drop-in sct.h (exact mode), the same source, flags and seed (and, for
// the floor of two tiny supervisors, against benchmarks/cpp_sct_floor.h).
//
//   cpp_sct_steps STEPS SUPERVISOR.yaml KINDS [SUPERVISOR.yaml KINDS]...
//       prints "SUPERVISOR CHECKSUM STEPS_PER_S" per file; KINDS is the file's ev_controllable
//       as a string ("00101": event 2 and 4 controllable)
//
// Events are registered as the published controllers do (member functions): a controllable
// event an action, an uncontrollable one a check. A step is called as a controller calls it:
// from its control step, out of line, through its SCT pointer (sct->run_step(), virtual), so
// that neither VM's step is inlined into the timing loop. The checks read a pseudo-random script
// (a quarter of them true per step), the actions count. CHECKSUM (FNV-1a of
// get_current_state_string() after each of the first kCheckedSteps steps) shows that both
// builds did the same work; the figure is the best of kRounds rounds of STEPS steps, each on a
// new SCT, ARGoS's "argos" generator seeded alike.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <argos3/core/utility/math/rng.h>

#include "sct.h"

namespace {

constexpr std::size_t kRows = 4096;
constexpr int kRounds = 5;
constexpr std::size_t kCheckedSteps = 4096;
constexpr argos::UInt32 kSeed = 1445;

class Controller {
public:
    Controller(SCT& sct, const std::string& kinds, const std::vector<std::vector<unsigned char>>& script)
        : sct_(&sct), script_(script) {
        for (const auto& entry : sct.events) events_.push_back(entry.second);
        std::size_t k = 0;
        for (const auto& entry : sct.events) {
            if (kinds.at(entry.second) == '1') {
                sct.add_callback(this, entry.first, &Controller::Act, NULL, &events_[k++]);
            } else {
                sct.add_callback(this, entry.first, NULL, &Controller::Check, &events_[k++]);
            }
        }
    }

    // A controller's ControlStep: its sensors (this step's row of the script), then the SCT.
    __attribute__((noinline)) void ControlStep(std::size_t step) {
        row_ = script_[step % kRows].data();
        sct_->run_step();
    }
    std::size_t acts() const { return acts_; }

private:
    unsigned char Check(void* data) { return row_[*static_cast<std::size_t*>(data)]; }
    void Act(void*) { ++acts_; }

    SCT* sct_;
    const std::vector<std::vector<unsigned char>>& script_;
    const unsigned char* row_ = nullptr;
    std::vector<std::size_t> events_;
    std::size_t acts_ = 0;
};

std::vector<std::vector<unsigned char>> make_script(std::size_t events) {
    std::uint32_t state = 12345;
    std::vector<std::vector<unsigned char>> rows(kRows, std::vector<unsigned char>(events));
    for (auto& row : rows) {
        for (unsigned char& value : row) {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            value = static_cast<unsigned char>((state >> 30) == 0);
        }
    }
    return rows;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4 || argc % 2 != 0) {
        std::fprintf(stderr, "usage: %s STEPS SUPERVISOR.yaml KINDS [SUPERVISOR.yaml KINDS]...\n", argv[0]);
        return 2;
    }
    const std::size_t steps = std::stoul(argv[1]);
    argos::CRandom::CreateCategory("argos", kSeed);
    for (int a = 2; a < argc; a += 2) {
        std::uint64_t checksum = 1469598103934665603u;
        double best = 0;
        for (int round = 0; round <= kRounds; ++round) {   // round 0: the checksum, untimed
            argos::CRandom::GetCategory("argos").ResetRNGs();
            SCT sct(argv[a]);
            const auto script = make_script(sct.events.size());
            Controller controller(sct, argv[a + 1], script);
            if (round == 0) {
                for (std::size_t i = 0; i < kCheckedSteps; ++i) {
                    controller.ControlStep(i);
                    for (char c : sct.get_current_state_string()) {
                        checksum = (checksum ^ static_cast<unsigned char>(c)) * 1099511628211u;
                    }
                }
                continue;
            }
            const auto start = std::chrono::steady_clock::now();
            for (std::size_t i = 0; i < steps; ++i) {
                controller.ControlStep(i);
            }
            const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
            best = std::max(best, static_cast<double>(steps) / elapsed.count());
            if (controller.acts() == 0) std::fprintf(stderr, "%s: no action ran\n", argv[a]);
        }
        std::printf("%s %016llx %.0f\n", argv[a], static_cast<unsigned long long>(checksum), best);
    }
    return 0;
}
