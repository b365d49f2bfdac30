// SPDX-License-Identifier: GPL-2.0-or-later
// The serializer constructors of YADE's base classes are inline in YADE and so not exported;
// the extern declarations in Plugin.hpp suppress their implicit instantiation, so they are
// instantiated once here. They do not need the bases' private serialize().
#include "Plugin.hpp"

#define SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(Base)                                                                                                            \
	template boost::archive::detail::oserializer<boost::archive::xml_oarchive, Base>::oserializer();                                                      \
	template boost::archive::detail::oserializer<boost::archive::binary_oarchive, Base>::oserializer();                                                   \
	template boost::archive::detail::iserializer<boost::archive::xml_iarchive, Base>::iserializer();                                                      \
	template boost::archive::detail::iserializer<boost::archive::binary_iarchive, Base>::iserializer();

SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(yade::Serializable)
SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(yade::FrictPhys)
SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(yade::FrictMat)
SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(yade::GlobalEngine)
SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(yade::IPhysFunctor)
SWELLDEM_INSTANTIATE_SERIALIZER_CTORS(yade::LawFunctor)
