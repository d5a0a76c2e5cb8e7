// What the energy study's loop functions and its three controllers share: the arena's strips,
// a robot's battery, and the interface through which the loop functions (which own the energy
// accounting, so every robot is charged by one rule) see each controller's role and activity.
#ifndef ENERGY_AGENT_H
#define ENERGY_AGENT_H

#include <cstdint>

namespace energy {

// The strips (design/STUDIES.md): 0.3 m wide, across the 1.6 m x 1.6 m arena, centred here.
constexpr double kStripHalfWidth = 0.15;
constexpr double kChargingX = -0.65;
constexpr double kTransferX = 0.35;
constexpr double kWorkX = 0.65;
constexpr double kArenaHalf = 0.8;
constexpr double kAtChargerRange = 0.14;   // a mobile-charger worker is "at charger" within this (m)

inline bool InStrip(double f_x, double f_centre) {
    return f_x >= f_centre - kStripHalfWidth && f_x <= f_centre + kStripHalfWidth;
}

enum class Role : std::uint8_t { None = 0, Worker = 1, Charger = 2 };

constexpr std::uint8_t kNobody = 0xFF;   // no partner

struct Battery {
    double Capacity = 100.0;
    double Energy = 100.0;
    bool Depleted = false;   // reached zero: the robot stops for the rest of the trial
};

// A controller as the loop functions see it.
class Agent {
public:
    virtual ~Agent() = default;
    virtual Role AgentRole() const = 0;
    virtual std::uint8_t Index() const = 0;     // per role, from the robot's id
    virtual std::uint8_t Partner() const = 0;   // charger: the worker it serves; worker: its charger
    virtual bool Moving() const = 0;            // wheels driven this step
    virtual bool Working() const = 0;           // a worker in its work state
    virtual bool Serving() const = 0;           // a charger in its transfer state
    virtual Battery& GetBattery() = 0;
};

}  // namespace energy

#endif
