// The mobile-charger worker: see energy_worker_mc_controller.h.
#include "energy_worker_mc_controller.h"

using energy::Mode;
using energy::Role;

// Wants energy: since its energy was low (moveToCharge) and until it is full again (moveToWork).
bool CEnergyWorkerMcController::Seeking() const { return m_eMode == Mode::ToCharge || m_eMode == Mode::Charge; }

// Its acknowledged charger is heard within 14 cm.
bool CEnergyWorkerMcController::AtCharger() const {
    const energy::Neighbour* psCharger = m_unPartner == energy::kNobody ? nullptr : Find(Role::Charger, m_unPartner);
    return psCharger != nullptr && psCharger->At.Length() <= energy::kAtChargerRange;
}

// Keeps its charger while that names it; takes the nearest charger that acknowledges it.
void CEnergyWorkerMcController::Protocol() {
    if (!Seeking()) return;
    KeepPartner(Role::Charger);
    if (m_unPartner == energy::kNobody) m_unPartner = NearestOffering(Role::Charger, m_unIndex);
}

std::uint8_t CEnergyWorkerMcController::Flags() const {
    return Seeking() && m_unPartner == energy::kNobody ? energy::kOffer : 0;
}

argos::CVector2 CEnergyWorkerMcController::Goal() const {
    switch (m_eMode) {
    case Mode::ToWork: return StripGoal(energy::kWorkX, false);
    case Mode::Work: return StripGoal(energy::kWorkX, true);
    case Mode::ToCharge:
    case Mode::Charge: {   // towards the acknowledged charger; still while waiting for one
        const energy::Neighbour* psCharger = m_unPartner == energy::kNobody ? nullptr : Find(Role::Charger, m_unPartner);
        if (psCharger) return Dock(*psCharger);
        // Our choice where the seed is silent: a worker that hears no charger at all (chargers
        // wait where they reached the transfer strip, and messages carry 0.533 m) searches along
        // the transfer strip towards its middle, where the chargers' neighbourhoods overlap.
        return Hears(Role::Charger) ? argos::CVector2() : PointGoal(energy::kTransferX, 0.0);
    }
    default: return StripGoal(energy::kChargingX, true);   // Start: charging in the base
    }
}

bool CEnergyWorkerMcController::Check_atCharger() { return m_eMode == Mode::Start ? In(energy::kChargingX) : AtCharger(); }
bool CEnergyWorkerMcController::Check_atWork() { return In(energy::kWorkX); }
bool CEnergyWorkerMcController::Check_highEnergy() { return HighEnergy(); }
bool CEnergyWorkerMcController::Check_lowEnergy() { return LowEnergy(); }
bool CEnergyWorkerMcController::Check_notAtCharger() { return !Check_atCharger(); }
bool CEnergyWorkerMcController::Check_notAtWork() { return !In(energy::kWorkX); }

void CEnergyWorkerMcController::On_charge() { m_eMode = Mode::Charge; }
void CEnergyWorkerMcController::On_moveToCharge() { m_eMode = Mode::ToCharge; }
void CEnergyWorkerMcController::On_moveToWork() {
    m_eMode = Mode::ToWork;
    m_unPartner = energy::kNobody;   // full, or the transfer ended with enough energy
}
void CEnergyWorkerMcController::On_work() { m_eMode = Mode::Work; }

REGISTER_CONTROLLER(CEnergyWorkerMcController, "energy_worker_mc_controller")
