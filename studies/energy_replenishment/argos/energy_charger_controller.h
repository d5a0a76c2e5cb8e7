// The mobile charger (the seed's Figure 8b, energy_charger.yaml): charges in the base, drives to
// the transfer strip, waits there and serves one requesting worker at a time (shareEnergy), and
// drives back to the base when its own energy is low.
#ifndef ENERGY_CHARGER_CONTROLLER_H
#define ENERGY_CHARGER_CONTROLLER_H

#include "energy_charger_base.h"
#include "energy_robot.h"

class CEnergyChargerController : public energy::CEnergyRobot<CEnergyChargerBase> {
public:
    energy::Role AgentRole() const override { return energy::Role::Charger; }

protected:
    void Protocol() override;
    std::uint8_t Flags() const override;
    argos::CVector2 Goal() const override;

    bool Check_atCharger() override;
    bool Check_atWork() override;
    bool Check_highEnergy() override;
    bool Check_lowEnergy() override;
    bool Check_notAtCharger() override;
    bool Check_notAtWork() override;

    void On_charge() override;
    void On_moveToCharge() override;
    void On_moveToWork() override;
    void On_shareEnergy() override;
};

#endif
