// ARGoS glue for the swarmvm C++ VM: a generator that draws from ARGoS's CRNG on request, and the
// per-robot VM seed.
//
// The default VM generator is the specified xorshift32 (docs/semantics.md), identical on every
// target. An ARGoS experiment may prefer the simulator's own random stream, seeded by the
// .argos file's random_seed, so that one seed drives the whole experiment; that gives up
// cross-target identity, so it is opt-in.
#ifndef SWARMVM_ARGOS_HPP
#define SWARMVM_ARGOS_HPP

#include <cstdint>
#include <string_view>

#include <argos3/core/utility/math/rng.h>

#include "swarmvm.hpp"

namespace swarmvm {

// xorshift32 unless built with an ARGoS CRNG, then that CRNG's uniform 32-bit draws.
class ArgosRng {
public:
    ArgosRng() = default;
    explicit ArgosRng(argos::CRandom::CRNG* rng) : rng_(rng) {}

    // ARGoS seeds and resets its CRNGs itself (from the experiment's random_seed), so a VM
    // reset re-seeds only the xorshift32 fallback.
    void seed(std::uint32_t seed) { fallback_.seed(seed); }

    std::uint32_t next() {
        if (rng_ == nullptr) return fallback_.next();
        return rng_->Uniform(full_);
    }

private:
    argos::CRandom::CRNG* rng_ = nullptr;
    XorShift32 fallback_;
    // The range the published VM draws from, built once: ARGoS's CRange constructor is out of
    // line and checks its bounds, a quarter of a draw's instructions when built per draw.
    argos::CRange<argos::UInt32> full_{0u, 0xFFFFFFFFu};
};

using ArgosVM = BasicVM<ArgosRng>;

// The VM seed of the robot `id` in an experiment seeded `seed`: the seed XOR FNV-1a (32 bits)
// of the id, so that robots sharing a configuration do not all make the same choices, and a
// robot's choices are reproducible from the seed and its id alone (docs/targets-cpp-python.md).
inline std::uint32_t robot_seed(std::uint32_t seed, std::string_view id) {
    std::uint32_t hash = 2166136261u;
    for (char c : id) hash = (hash ^ static_cast<unsigned char>(c)) * 16777619u;
    return seed ^ hash;
}

}  // namespace swarmvm

#endif  // SWARMVM_ARGOS_HPP
