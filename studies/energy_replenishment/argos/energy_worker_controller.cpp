// The fixed-charger worker: see energy_worker_controller.h.
#include "energy_worker_controller.h"

using energy::Mode;

argos::CVector2 CEnergyWorkerController::Goal() const {
    switch (m_eMode) {
    case Mode::ToWork: return StripGoal(energy::kWorkX, false);
    case Mode::Work: return StripGoal(energy::kWorkX, true);
    case Mode::ToCharge: return StripGoal(energy::kChargingX, false);
    default: return StripGoal(energy::kChargingX, true);   // Start, Charge: stay in the base
    }
}

bool CEnergyWorkerController::Check_atCharger() { return In(energy::kChargingX); }
bool CEnergyWorkerController::Check_atWork() { return In(energy::kWorkX); }
bool CEnergyWorkerController::Check_highEnergy() { return HighEnergy(); }
bool CEnergyWorkerController::Check_lowEnergy() { return LowEnergy(); }
bool CEnergyWorkerController::Check_notAtCharger() { return !In(energy::kChargingX); }
bool CEnergyWorkerController::Check_notAtWork() { return !In(energy::kWorkX); }

void CEnergyWorkerController::On_charge() { m_eMode = Mode::Charge; }
void CEnergyWorkerController::On_moveToCharge() { m_eMode = Mode::ToCharge; }
void CEnergyWorkerController::On_moveToWork() { m_eMode = Mode::ToWork; }
void CEnergyWorkerController::On_work() { m_eMode = Mode::Work; }

REGISTER_CONTROLLER(CEnergyWorkerController, "energy_worker_controller")
