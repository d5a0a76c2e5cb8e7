// The mobile charger: see energy_charger_controller.h. Its "work" region is the transfer strip.
#include "energy_charger_controller.h"

using energy::Mode;
using energy::Role;

// While serving: keeps its worker while that names it, else acknowledges the nearest request.
void CEnergyChargerController::Protocol() {
    if (m_eMode != Mode::Serve) return;
    KeepPartner(Role::Worker);
    if (m_unPartner == energy::kNobody) m_unPartner = NearestOffering(Role::Worker, energy::kNobody);
}

std::uint8_t CEnergyChargerController::Flags() const {
    return m_eMode == Mode::Serve && m_unPartner == energy::kNobody ? energy::kOffer : 0;
}

argos::CVector2 CEnergyChargerController::Goal() const {
    switch (m_eMode) {
    case Mode::ToWork: return StripGoal(energy::kTransferX, false);
    case Mode::Serve: return StripGoal(energy::kTransferX, true);
    case Mode::ToCharge: return StripGoal(energy::kChargingX, false);
    default: return StripGoal(energy::kChargingX, true);   // Start, Charge
    }
}

bool CEnergyChargerController::Check_atCharger() { return In(energy::kChargingX); }
bool CEnergyChargerController::Check_atWork() { return In(energy::kTransferX); }
bool CEnergyChargerController::Check_highEnergy() { return HighEnergy(); }
bool CEnergyChargerController::Check_lowEnergy() { return LowEnergy(); }
bool CEnergyChargerController::Check_notAtCharger() { return !In(energy::kChargingX); }
bool CEnergyChargerController::Check_notAtWork() { return !In(energy::kTransferX); }

void CEnergyChargerController::On_charge() { m_eMode = Mode::Charge; }
void CEnergyChargerController::On_moveToCharge() {
    m_eMode = Mode::ToCharge;
    m_unPartner = energy::kNobody;   // a transfer in progress ends
}
void CEnergyChargerController::On_moveToWork() { m_eMode = Mode::ToWork; }
void CEnergyChargerController::On_shareEnergy() { m_eMode = Mode::Serve; }

REGISTER_CONTROLLER(CEnergyChargerController, "energy_charger_controller")
