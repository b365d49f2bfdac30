// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/ContactKindParams.hpp"

#include "core/Validate.hpp"

namespace swelldem::core {

void ContactKindParams::validate() const
{
    if (behaviour == Behaviour::Elastic) requirePositive("contactModulus E_c [Pa]", contactModulus);
    else b3.validate();
    if (behaviour == Behaviour::Viscoelastic) chain.validate();
    requirePositive("shearRatio alpha [-]", shearRatio);
    if (swelling) {
        requireNonNegative("swellingDisplacementInf [m]", swellingDisplacementInf);
        requireNonNegative("swellingStrainInf [-]", swellingStrainInf);
        require(!(swellingDisplacementInf > 0 && swellingStrainInf > 0), "swellingStrainInf [-]",
                swellingStrainInf, "0 when swellingDisplacementInf > 0 (give one of the two)");
        SwellingKinetics(tauC, tauL, referenceTemperature, Uc, UL);  // validates the kinetics
    }
    strength.validate();
}

}  // namespace swelldem::core
