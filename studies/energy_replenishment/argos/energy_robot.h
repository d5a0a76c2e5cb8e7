// The application layer every controller of the energy study shares, between a generated
// `C<Name>Base` (the supervisor's VM and event binding) and the user's controller (the checks
// and actions of the private events): sensors, the battery and its thresholds, the virtual-force
// motion of the seed and the range-and-bearing payload of the charger/worker protocol.
//
// One control step: read the sensors and neighbours, run the role's protocol, step the VM (its
// checks read what was sensed, its actions set the mode), then drive by the virtual force
// towards the mode's goal and broadcast the payload. The loop functions do the energy
// accounting after the physics step, from Moving(), Working(), Serving() and Partner().
//
// <params><energy capacity="100" move="0.1" core="0.005" high="0.99" margin="10" speed="12"
//                 noise="0.05" alpha="1" beta="100" gamma="1" sigma="0.1" lambda="24"/></params>
// (rates per control step, speed in cm/s, noise the steering noise's standard deviation, rad).
#ifndef ENERGY_ROBOT_H
#define ENERGY_ROBOT_H

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <argos3/core/utility/math/rng.h>
#include <argos3/core/utility/math/vector2.h>
#include <argos3/plugins/robots/e-puck/control_interface/ci_epuck_proximity_sensor.h>
#include <argos3/plugins/robots/generic/control_interface/ci_positioning_sensor.h>
#include <argos3/plugins/robots/generic/control_interface/ci_range_and_bearing_sensor.h>

#include "energy_agent.h"

namespace energy {

// The range-and-bearing payload after the two bytes of the VM's message code.
enum Byte : std::size_t { kRole = 2, kIndex = 3, kFlags = 4, kPartner = 5, kPayloadSize = 6 };
constexpr std::uint8_t kOffer = 1;   // worker: requesting energy; charger: free to serve

struct Neighbour {
    argos::CVector2 At;   // relative position in the robot's frame, m
    Role Who = Role::None;
    std::uint8_t Index = kNobody;
    std::uint8_t Flags = 0;
    std::uint8_t Partner = kNobody;
};

// What the last action of the supervisor asked the robot to do.
enum class Mode { Start, ToWork, Work, ToCharge, Charge, Serve };

template <class TBase>
class CEnergyRobot : public TBase, public Agent {
public:
    void Init(argos::TConfigurationNode& t_node) override {
        if (argos::NodeExists(t_node, "energy")) {
            argos::TConfigurationNode& tEnergy = argos::GetNode(t_node, "energy");
            argos::GetNodeAttributeOrDefault(tEnergy, "capacity", m_sBattery.Capacity, m_sBattery.Capacity);
            argos::GetNodeAttributeOrDefault(tEnergy, "move", m_fMove, m_fMove);
            argos::GetNodeAttributeOrDefault(tEnergy, "core", m_fCore, m_fCore);
            argos::GetNodeAttributeOrDefault(tEnergy, "high", m_fHigh, m_fHigh);
            argos::GetNodeAttributeOrDefault(tEnergy, "margin", m_fMargin, m_fMargin);
            argos::GetNodeAttributeOrDefault(tEnergy, "speed", m_fMaxSpeed, m_fMaxSpeed);
            argos::GetNodeAttributeOrDefault(tEnergy, "noise", m_fNoise, m_fNoise);
            argos::GetNodeAttributeOrDefault(tEnergy, "inset", m_fInset, m_fInset);
            argos::GetNodeAttributeOrDefault(tEnergy, "alpha", m_fAlpha, m_fAlpha);
            argos::GetNodeAttributeOrDefault(tEnergy, "beta", m_fBeta, m_fBeta);
            argos::GetNodeAttributeOrDefault(tEnergy, "gamma", m_fGamma, m_fGamma);
            argos::GetNodeAttributeOrDefault(tEnergy, "sigma", m_fSigma, m_fSigma);
            argos::GetNodeAttributeOrDefault(tEnergy, "lambda", m_fLambda, m_fLambda);
        }
        m_pcPosition = this->template GetSensor<argos::CCI_PositioningSensor>("positioning");
        m_pcProximity = this->template GetSensor<argos::CCI_EPuckProximitySensor>("epuck_proximity");
        m_pcRNG = argos::CRandom::CreateRNG("argos");
        m_unIndex = IndexOf(this->GetId());
        TBase::Init(t_node);
    }

    void ControlStep() override {
        if (m_sBattery.Depleted) {   // no energy: no sensing, no VM, no motion, no messages
            this->m_pcWheels->SetLinearVelocity(0.0, 0.0);
            this->m_pcRABAct->ClearData();
            m_bMoving = false;
            return;
        }
        Sense();
        Protocol();
        TBase::ControlStep();   // clears the payload, steps the VM: checks, then the action
        Drive(Goal());
        Broadcast();
    }

    void Reset() override {
        TBase::Reset();
        m_sBattery.Energy = m_sBattery.Capacity;
        m_sBattery.Depleted = false;
        m_eMode = Mode::Start;
        m_unPartner = kNobody;
        m_unMissed = 0;
        m_bMoving = false;
        m_vecNeighbours.clear();
    }

    std::uint8_t Index() const override { return m_unIndex; }
    std::uint8_t Partner() const override { return m_unPartner; }
    bool Moving() const override { return m_bMoving; }
    bool Working() const override { return m_eMode == Mode::Work; }
    bool Serving() const override { return m_eMode == Mode::Serve; }
    Battery& GetBattery() override { return m_sBattery; }

protected:
    // The role's part of the protocol, before the VM step (default: none).
    virtual void Protocol() {}
    // Flags of the payload (kOffer or 0).
    virtual std::uint8_t Flags() const { return 0; }
    // The attraction goal in the robot's frame for the current mode.
    virtual argos::CVector2 Goal() const = 0;

    double X() const { return m_cPosition.GetX(); }
    bool In(double f_centre) const { return InStrip(X(), f_centre); }

    bool HighEnergy() const { return m_sBattery.Energy >= m_fHigh * m_sBattery.Capacity; }
    // Dynamic low threshold: the energy to drive back to the charging strip at full speed, plus
    // the margin (design/STUDIES.md).
    bool LowEnergy() const {
        const double fDistance = std::max(0.0, X() - (kChargingX + kStripHalfWidth));
        const double fSteps = fDistance / (m_fMaxSpeed / 100.0) * kTicksPerSecond;
        return m_sBattery.Energy <= fSteps * (m_fMove + m_fCore) + m_fMargin;
    }

    // Towards (x, own y) while heading for a strip; once in `f_centre`'s strip, stay.
    argos::CVector2 StripGoal(double f_centre, bool b_stay) const {
        const double fX = b_stay ? std::clamp(X(), f_centre - kStripHalfWidth + m_fInset, f_centre + kStripHalfWidth - m_fInset)
                                 : f_centre;
        return ToLocal(argos::CVector2(fX - X(), 0.0));
    }

    // Towards a point of the arena.
    argos::CVector2 PointGoal(double f_x, double f_y) const {
        return ToLocal(argos::CVector2(f_x - X(), f_y - m_cPosition.GetY()));
    }

    bool Hears(Role e_who) const {
        return std::any_of(m_vecNeighbours.begin(), m_vecNeighbours.end(), [e_who](const Neighbour& s_n) { return s_n.Who == e_who; });
    }

    const Neighbour* Find(Role e_who, std::uint8_t un_index) const {
        for (const Neighbour& sN : m_vecNeighbours) {
            if (sN.Who == e_who && sN.Index == un_index) return &sN;
        }
        return nullptr;
    }

    // Keeps the partner while it is heard naming this robot; drops it when it names another,
    // or after kPatience steps without hearing it name this one (the handshake takes two).
    void KeepPartner(Role e_who) {
        if (m_unPartner == kNobody) return;
        const Neighbour* psN = Find(e_who, m_unPartner);
        const bool bConfirmed = psN != nullptr && psN->Partner == m_unIndex;
        const bool bTaken = psN != nullptr && psN->Partner != kNobody && psN->Partner != m_unIndex;
        m_unMissed = bConfirmed ? 0 : m_unMissed + 1;
        if (bTaken || m_unMissed > kPatience) {
            m_unPartner = kNobody;
            m_unMissed = 0;
        }
    }

    // The nearest neighbour of role `e_who` that offers itself and names `un_partner` (kNobody:
    // anyone), or kNobody.
    std::uint8_t NearestOffering(Role e_who, std::uint8_t un_partner) const {
        const Neighbour* psBest = nullptr;
        for (const Neighbour& sN : m_vecNeighbours) {
            if (sN.Who != e_who || sN.Partner != un_partner) continue;
            if (un_partner == kNobody && !(sN.Flags & kOffer)) continue;
            if (psBest == nullptr || sN.At.Length() < psBest->At.Length()) psBest = &sN;
        }
        return psBest ? psBest->Index : kNobody;
    }

    // A neighbour this robot and that one have chosen for a transfer.
    bool IsPartner(const Neighbour& s_n) const {
        return m_unPartner != kNobody && s_n.Index == m_unPartner && s_n.Partner == m_unIndex && s_n.Who != AgentRole();
    }

    // Towards a docking distance from a neighbour (within the 14 cm of a transfer).
    static argos::CVector2 Dock(const Neighbour& s_n) {
        const double fD = s_n.At.Length();
        return fD > kDockDistance ? s_n.At * ((fD - kDockDistance) / fD) : argos::CVector2();
    }

    Battery m_sBattery;
    Mode m_eMode = Mode::Start;
    std::uint8_t m_unIndex = 0;
    std::uint8_t m_unPartner = kNobody;
    std::vector<Neighbour> m_vecNeighbours;

private:
    static constexpr double kTicksPerSecond = 10.0;
    static constexpr double kStop = 0.01;         // a smaller force leaves the robot still
    static constexpr double kAxle = 0.053;        // e-puck inter-wheel distance (m)
    static constexpr unsigned kPatience = 10;     // steps a partner may go unconfirmed
    static constexpr double kDockDistance = 0.09; // centre to centre, m (e-pucks touch at 0.07)

    // ids are a role letter and a number ("w3", "c0").
    static std::uint8_t IndexOf(const std::string& str_id) {
        std::size_t unDigits = str_id.size();
        while (unDigits > 0 && std::isdigit(static_cast<unsigned char>(str_id[unDigits - 1]))) --unDigits;
        return static_cast<std::uint8_t>(unDigits < str_id.size() ? std::stoul(str_id.substr(unDigits)) : 0);
    }

    argos::CVector2 ToLocal(const argos::CVector2& c_global) const {
        argos::CVector2 cLocal(c_global);
        cLocal.Rotate(-m_cYaw);
        return cLocal;
    }

    void Sense() {
        const argos::CCI_PositioningSensor::SReading& sPos = m_pcPosition->GetReading();
        m_cPosition.Set(sPos.Position.GetX(), sPos.Position.GetY());
        argos::CRadians cY, cX;
        sPos.Orientation.ToEulerAngles(m_cYaw, cY, cX);
        m_vecNeighbours.clear();
        for (const argos::CCI_RangeAndBearingSensor::SPacket& sPacket : this->m_pcRABSens->GetReadings()) {
            if (sPacket.Data.Size() < kPayloadSize) continue;
            Neighbour sN;
            sN.At.FromPolarCoordinates(sPacket.Range / 100.0, sPacket.HorizontalBearing);
            sN.Who = static_cast<Role>(sPacket.Data[kRole]);
            sN.Index = sPacket.Data[kIndex];
            sN.Flags = sPacket.Data[kFlags];
            sN.Partner = sPacket.Data[kPartner];
            m_vecNeighbours.push_back(sN);
        }
    }

    // u = alpha u_attraction + beta u_neighbours + gamma u_obstacles (the seed's virtual force),
    // turned into wheel speeds: forward in proportion to the force along the heading, turning
    // towards it; a small steering noise.
    void Drive(const argos::CVector2& c_goal) {
        const double fVMax = m_fMaxSpeed / 100.0;
        argos::CVector2 cForce;
        const double fGoal = c_goal.Length();
        if (fGoal > 0.0) cForce += c_goal * (std::min(fGoal, fVMax) / fGoal * m_fAlpha);
        argos::CVector2 cRepulsion;
        for (const Neighbour& sN : m_vecNeighbours) {
            if (IsPartner(sN)) continue;   // partners dock for a transfer: no repulsion between them
            const double fD = std::max(sN.At.Length(), 1e-3);
            cRepulsion -= sN.At * (std::pow(m_fSigma / fD, m_fLambda) / fD);
        }
        if (!m_vecNeighbours.empty()) cForce += cRepulsion * (m_fBeta / static_cast<double>(m_vecNeighbours.size()));
        argos::CVector2 cObstacles;   // (d_max - d_j) / d_max is the reading's value in [0, 1]
        for (const argos::CCI_EPuckProximitySensor::SReading& sR : m_pcProximity->GetReadings()) {
            cObstacles -= argos::CVector2(sR.Value, sR.Angle);
        }
        cForce += cObstacles * (m_fGamma / 8.0);
        if (cForce.Length() < kStop) {
            this->m_pcWheels->SetLinearVelocity(0.0, 0.0);
            m_bMoving = false;
            return;
        }
        double fAngle = cForce.Angle().SignedNormalize().GetValue();
        if (m_fNoise > 0.0) fAngle += m_pcRNG->Gaussian(m_fNoise);
        const double fForward = m_fMaxSpeed * std::min(1.0, cForce.Length() / fVMax) * std::max(0.0, std::cos(fAngle));
        const double fTurn = 4.0 * fAngle * kAxle * 50.0;   // cm/s of wheel difference, 4 rad/s per rad
        double fLeft = fForward - fTurn, fRight = fForward + fTurn;
        const double fScale = std::max({1.0, std::abs(fLeft) / m_fMaxSpeed, std::abs(fRight) / m_fMaxSpeed});
        fLeft /= fScale;
        fRight /= fScale;
        this->m_pcWheels->SetLinearVelocity(fLeft, fRight);
        m_bMoving = fLeft != 0.0 || fRight != 0.0;
    }

    void Broadcast() {
        this->m_pcRABAct->SetData(kRole, static_cast<argos::UInt8>(AgentRole()));
        this->m_pcRABAct->SetData(kIndex, m_unIndex);
        this->m_pcRABAct->SetData(kFlags, Flags());
        this->m_pcRABAct->SetData(kPartner, m_unPartner);
    }

    argos::CCI_PositioningSensor* m_pcPosition = nullptr;
    argos::CCI_EPuckProximitySensor* m_pcProximity = nullptr;
    argos::CRandom::CRNG* m_pcRNG = nullptr;
    argos::CVector2 m_cPosition;
    argos::CRadians m_cYaw;
    unsigned m_unMissed = 0;
    bool m_bMoving = false;
    double m_fMove = 0.1, m_fCore = 0.005, m_fHigh = 0.99, m_fMargin = 10.0, m_fMaxSpeed = 12.0, m_fNoise = 0.05;
    double m_fAlpha = 1.0, m_fBeta = 100.0, m_fGamma = 1.0, m_fSigma = 0.1, m_fLambda = 24.0;
    double m_fInset = 0.02;   // once inside a strip, stay at least this far from its edges (m; 0.15: its centre line)
};

}  // namespace energy

#endif
