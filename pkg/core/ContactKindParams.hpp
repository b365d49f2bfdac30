// SPDX-License-Identifier: GPL-2.0-or-later
// Parameters shared by all contacts of one kind (MORTAR, ITZ, AGG, ...): one set per kind, kept
// apart from the per-contact state (ContactState) and geometry (ContactGeometry).
#pragma once

#include "core/B3Compliance.hpp"
#include "core/BrittleContact.hpp"
#include "core/KelvinChain.hpp"
#include "core/SolidificationCreep.hpp"
#include "core/SwellingKinetics.hpp"

namespace swelldem::core {

enum class Behaviour {
    Elastic,       ///< constant contact modulus E_c; no Kelvin state
    AgingElastic,  ///< dF = kn(t*) du with E(t) = 1/J(t + elasticLag, t) of the B3 params; no Kelvin state
    Viscoelastic   ///< solidification theory (B3) with a Kelvin chain per direction
};

struct ContactKindParams {
    Behaviour behaviour = Behaviour::Elastic;
    double contactModulus = 0;   ///< E_c [Pa] (Elastic kinds), > 0
    B3Params b3;                 ///< B3 parameters (AgingElastic, Viscoelastic)
    double shearRatio = 1.0;     ///< alpha = ks/kn [-], > 0
    KelvinChainOptions chain;    ///< Kelvin chain construction (Viscoelastic)
    InteriorTime interiorTime = InteriorTime::Geometric;  ///< t* rule (aging kinds)

    bool swelling = false;              ///< imposed swelling displacement on/off
    double swellingDisplacementInf = 0; ///< d_inf [m] (paper: eps_inf x 2 R_mean), >= 0
    double swellingStrainInf = 0;       ///< alternative: d_inf = eps_inf x L per contact [-], >= 0
    double tauC = 50.0;                 ///< characteristic time at T0 [day]
    double tauL = 100.0;                ///< latency time at T0 [day]
    double referenceTemperature = SwellingKinetics::kT0;  ///< T0 [K]
    double Uc = SwellingKinetics::kUc;  ///< [K]
    double UL = SwellingKinetics::kUL;  ///< [K]

    BrittleStrength strength;           ///< damage (off by default)

    /// Throws std::invalid_argument naming the first parameter out of range; only the
    /// parameters the behaviour uses are checked.
    void validate() const;
};

}  // namespace swelldem::core
