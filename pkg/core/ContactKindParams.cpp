// SPDX-License-Identifier: GPL-2.0-or-later
#include "core/ContactKindParams.hpp"

#include "core/Validate.hpp"

#include <stdexcept>
#include <string>

namespace swelldem::core {

const char* behaviourName(Behaviour b)
{
    switch (b) {
    case Behaviour::Elastic: return "elastic";
    case Behaviour::AgingElastic: return "aging-elastic";
    case Behaviour::Viscoelastic: return "viscoelastic";
    }
    return "?";
}

Behaviour parseBehaviour(const std::string& name)
{
    for (Behaviour b : {Behaviour::Elastic, Behaviour::AgingElastic, Behaviour::Viscoelastic})
        if (name == behaviourName(b)) return b;
    throw std::invalid_argument("swelldem: behaviour = '" + name +
                                "' is out of range; allowed: 'elastic', 'aging-elastic', 'viscoelastic'");
}

ContactKindParams::ContactKindParams()
{
#define SWELLDEM_KIND_DEFAULT(type, name, member, def, doc) member = def;
    SWELLDEM_KIND_PARAMETERS(SWELLDEM_KIND_DEFAULT)
#undef SWELLDEM_KIND_DEFAULT
}

bool ContactKindParams::operator==(const ContactKindParams& o) const
{
#define SWELLDEM_KIND_SAME(type, name, member, def, doc) && member == o.member
    return behaviour == o.behaviour && interiorTime == o.interiorTime && swellingStrainInf == o.swellingStrainInf &&
           b3.n == o.b3.n && b3.m == o.b3.m && b3.lambda0 == o.b3.lambda0 &&
           chain.order == o.chain.order && chain.richardson == o.chain.richardson &&
           chain.marginBelow == o.chain.marginBelow SWELLDEM_KIND_PARAMETERS(SWELLDEM_KIND_SAME);
#undef SWELLDEM_KIND_SAME
}

void ContactKindParams::validate() const
{
    if (behaviour == Behaviour::Elastic) requirePositive("young (contact modulus E_c) [Pa]", contactModulus);
    else b3.validate();
    if (behaviour == Behaviour::Viscoelastic) chain.validate();
    requirePositive("shearRatio alpha [-]", shearRatio);
    TemperatureHistory::validate(temperatureDays, temperatures);
    if (behaviour != Behaviour::Elastic && thermal.on) thermal.validate();
    if (swelling) {
        requireNonNegative("swellDispInf [m]", swellingDisplacementInf);
        requireNonNegative("swellingStrainInf [-]", swellingStrainInf);
        require(!(swellingDisplacementInf > 0 && swellingStrainInf > 0), "swellingStrainInf [-]",
                swellingStrainInf, "0 when swellDispInf > 0 (give one of the two)");
        SwellingKinetics(tauC, tauL, referenceTemperature, Uc, UL);  // validates the kinetics
    }
    strength.validate();
}

}  // namespace swelldem::core
