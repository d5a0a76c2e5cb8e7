// The worker of the mobile-charger strategy (the seed's Figure 8c, energy_worker_mc.yaml): works
// in the work strip; when its energy is low it stops and requests energy until a mobile charger
// acknowledges, approaches that charger and receives energy within 14 cm of it. If the transfer
// ends early it goes back to work with enough energy, else it requests again.
#ifndef ENERGY_WORKER_MC_CONTROLLER_H
#define ENERGY_WORKER_MC_CONTROLLER_H

#include "energy_robot.h"
#include "energy_worker_mc_base.h"

class CEnergyWorkerMcController : public energy::CEnergyRobot<CEnergyWorkerMcBase> {
public:
    energy::Role AgentRole() const override { return energy::Role::Worker; }

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
    void On_work() override;

private:
    bool Seeking() const;
    bool AtCharger() const;
};

#endif
