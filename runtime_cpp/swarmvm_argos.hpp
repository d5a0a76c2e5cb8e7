// ARGoS glue for the swarmvm C++ VM: a generator that draws from ARGoS's CRNG on request, the
// per-robot seed and the message codes of public events.
//
// The default VM generator is the specified xorshift32 (docs/semantics.md), identical on every
// target. An ARGoS experiment may prefer the simulator's own random stream, seeded by the
// .argos file's random_seed, so that one seed drives the whole experiment; that gives up
// cross-target identity, so it is opt-in.
#ifndef SWARMVM_ARGOS_HPP
#define SWARMVM_ARGOS_HPP

#include <cstdint>
#include <string>
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
        return rng_->Uniform(argos::CRange<argos::UInt32>(0u, 0xFFFFFFFFu));
    }

private:
    argos::CRandom::CRNG* rng_ = nullptr;
    XorShift32 fallback_;
};

using ArgosVM = BasicVM<ArgosRng>;

// FNV-1a (32 bits) of a text: the robot id in robot_seed, the message name in message_code.
constexpr std::uint32_t fnv1a(std::string_view text) {
    std::uint32_t hash = 2166136261u;
    for (char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 16777619u;
    return hash;
}

// The VM seed of the robot `id` in an experiment seeded `seed`: the seed XOR FNV-1a of the id,
// so that robots sharing a configuration do not all make the same choices, and a robot's
// choices are reproducible from the seed and its id alone (docs/targets-cpp-python.md).
inline std::uint32_t robot_seed(std::uint32_t seed, const std::string& id) { return seed ^ fnv1a(id); }

// The 16-bit code a public event's message travels as over range-and-bearing: FNV-1a of the
// message name ("x" for both the sender's EV_x and the receiver's EV__x), folded to 16 bits,
// never 0 (0 means "no message"). By name, because sender and receiver usually run
// different supervisors, whose event indices differ.
constexpr std::uint16_t message_code(std::string_view name) {
    const std::uint32_t hash = fnv1a(name);
    const auto code = static_cast<std::uint16_t>((hash >> 16) ^ (hash & 0xFFFFu));
    return code != 0 ? code : 1;
}

}  // namespace swarmvm

#endif  // SWARMVM_ARGOS_HPP
