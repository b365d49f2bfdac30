// SPDX-License-Identifier: GPL-2.0-or-later
// How swelldem defines its own YADE classes without YADE's headers: one attribute list per class
// (an X-macro) generates the members, their Python properties with docstrings, pySetAttr/pyDict
// and boost::serialization, the way YADE's own class macros do for in-tree classes.
#pragma once
#include "Engines.hpp"
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/archive/xml_iarchive.hpp>
#include <boost/archive/xml_oarchive.hpp>
// The archive headers must precede export.hpp: the export machinery then instantiates the
// pointer serializers for exactly the four archive types YADE's O.save/O.load use.
#include <boost/serialization/base_object.hpp>
#include <boost/serialization/export.hpp>
#include <boost/serialization/factory.hpp>
#include <boost/serialization/nvp.hpp>
#include <boost/serialization/shared_ptr.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>
#include <limits>

namespace yade {
namespace swelldem_py {
	namespace bp = boost::python;

	// Python constructor accepting keyword attributes only, like YADE's classes.
	template <typename T> shared_ptr<T> constructWithAttrs(bp::tuple& args, bp::dict& kw)
	{
		shared_ptr<T> instance(new T);
		instance->pyHandleCustomCtorArgs(args, kw);
		if (bp::len(args) > 0) throw std::invalid_argument(instance->getClassName() + ": only keyword arguments are accepted.");
		if (bp::len(kw) > 0) {
			instance->pyUpdateAttrs(kw);
			instance->callPostLoad();
		}
		return instance;
	}

	// boost::python has no raw constructor; this is the usual make_constructor + raw_function pairing.
	template <class F> struct RawCtor {
		explicit RawCtor(F fn)
		        : ctor(bp::make_constructor(fn))
		{
		}
		PyObject* operator()(PyObject* args, PyObject* kw)
		{
			bp::object all(bp::handle<>(bp::borrowed(args)));
			bp::dict   kwd = kw ? bp::dict(bp::handle<>(bp::borrowed(kw))) : bp::dict();
			bp::object self(all[0]);
			bp::object rest(all.slice(1, bp::len(all)));
			return bp::incref(bp::object(ctor(self, rest, kwd)).ptr());
		}
		bp::object ctor;
	};
	template <class F> bp::object rawConstructor(F fn)
	{
		return bp::detail::make_raw_function(bp::objects::py_function(
		        RawCtor<F>(fn), boost::mpl::vector2<void, bp::object>(), 1, (std::numeric_limits<unsigned>::max)()));
	}

	// Registers T with YADE's ClassFactory (what YADE's REGISTER_FACTORABLE does for its classes).
	template <class T> struct FactoryRegistration {
		static Factorable*            create() { return new T; }
		static shared_ptr<Factorable> createShared() { return shared_ptr<Factorable>(new T); }
		static void*                  createPure() { return new T; }
		explicit FactoryRegistration(const char* name) { ClassFactory::instance().registerFactorable(name, &create, &createShared, &createPure); }
	};
} // namespace swelldem_py
} // namespace yade

// ---- the plugin's version in saved scenes. Each plugin class is saved with the plugin's version as
// its Boost class version (PluginRegistry.cpp), which Boost writes once per class and archive, before
// the object's fields, and gives back on load whatever it is: a scene is refused there, before a
// field of another layout could be misread (binary archives) or fail on a tag (XML archives).
#ifndef SWELLDEM_SCENE_VERSION
#error "SWELLDEM_SCENE_VERSION (MAJOR * 10000 + MINOR * 100 + PATCH) is set by pkg/yade/CMakeLists.txt"
#endif
namespace yade {
namespace swelldem_py {
	constexpr unsigned kSceneVersion = SWELLDEM_SCENE_VERSION;
	inline std::string versionText(unsigned v)
	{
		return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
	}
	// A saved scene is read only by the plugin version that wrote it: fields are added, removed or
	// reordered between versions, and Boost reads them by position.
	inline void requireSceneVersion(const char* className, unsigned saved)
	{
		if (saved == kSceneVersion) return;
		const std::string by = saved == 0 ? "a swelldem that did not record its version (0.1.0 or earlier)" : "swelldem " + versionText(saved);
		throw std::runtime_error("swelldem: this scene was saved by " + by + "; the loaded plugin is swelldem " + versionText(kSceneVersion)
		                         + " (first saved object: " + className + "). A scene is loaded only by the version that saved it: load it with "
		                         + (saved == 0 ? string("that swelldem") : "swelldem " + versionText(saved))
		                         + ", or build the scene again with this one (rerun its script)");
	}
}
}

// ---- attribute lists: #define ATTRS(X) X(type, name, default, flags, "doc [unit]") ...
// flags say what an attribute is to the user: a setting (writable; validated by postLoad, which a
// Python assignment calls, restoring the old value if it throws), a result (read-only in Python),
// an internal (saved but not shown in Python); Transient ones are not saved.
namespace yade {
namespace swelldem_attr {
	constexpr unsigned Setting = 0, Result = 1, Internal = 2, Transient = 4;
}
namespace swelldem_py {
	// Classes may define afterLoad(): run once a saved object is read back (not on Python assignments).
	template <class T> auto afterLoadImpl(T& t, int) -> decltype(t.afterLoad(), void()) { t.afterLoad(); }
	template <class T> void afterLoadImpl(T&, long) { }
	template <class T> void afterLoad(T& t) { afterLoadImpl(t, 0); }
	template <class T> struct IsVector : std::false_type { };
	template <class E, class A> struct IsVector<std::vector<E, A>> : std::true_type { };
	template <class T> struct IsObject : std::false_type { };
	template <class E> struct IsObject<shared_ptr<E>> : std::true_type {
		using Element = E;
	};
	template <class T> std::string shown(const T& v)
	{
		if constexpr (IsObject<T>::value) {
			return v ? v->getClassName() : std::string("None");
		} else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
			std::ostringstream s;
			s << v;
			return s.str();
		} else if constexpr (IsVector<T>::value) {
			// a list of numbers, as Python prints it (long ones cut: the message names the bad entry)
			std::string out = "[";
			for (size_t i = 0; i < v.size() && i < 8; ++i)
				out += (i ? ", " : "") + shown(v[i]);
			return out + (v.size() > 8 ? ", ...]" : "]");
		} else
			return "(the value given)";
	}
	// Assignment from Python: validate through postLoad; a refused value leaves the object as it was
	// and the error names the attribute as the user wrote it (the core names its own parameter).
	template <class C, class T> std::invalid_argument refused(const C& self, const char* name, const T& value, const T& old, const std::exception& why)
	{
		return std::invalid_argument(self.getClassName() + "." + name + " = " + shown(value) + " refused, the old value " + shown(old)
		                             + " kept: " + why.what());
	}
	template <class C, class T> void setChecked(C& self, const char* name, T& member, const T& value)
	{
		T old  = member;
		member = value;
		try {
			self.postLoad();
		} catch (const std::exception& e) {
			member = old;
			throw refused(self, name, value, old, e);
		} catch (...) {
			member = old;
			throw;
		}
	}
	// Classes may define checkObject(name, value): what an object attribute may be set to from Python
	// (and only from there: a default-made or saved object may hold what a user may not set, e.g. a
	// SwellPhys without its kind, which YADE's own save/load test makes).
	template <class C, class V> auto checkObjectImpl(const C& c, const char* name, const V& v, int) -> decltype(c.checkObject(name, v), void())
	{
		c.checkObject(name, v);
	}
	template <class C, class V> void checkObjectImpl(const C&, const char*, const V&, long) { }
	// An object attribute (a shared_ptr, e.g. a ContactKind) takes any Python value: boost.python's own
	// conversion would refuse another type with a bare signature mismatch, and its pySetAttr path
	// (constructor keywords, updateAttrs) would keep a refused value. Here a value of another type is
	// refused in the plugin's form, then the class's checkObject and postLoad, and a refused value is
	// not kept, whichever path set it.
	template <class C, class E> void setObject(C& self, const char* name, shared_ptr<E>& member, const boost::python::object& value)
	{
		shared_ptr<E> v;
		if (!value.is_none()) {
			boost::python::extract<shared_ptr<E>> x(value);
			if (!x.check()) {
				const std::string given = boost::python::extract<std::string>(boost::python::str(value.attr("__repr__")()));
				throw std::invalid_argument("swelldem: " + self.getClassName() + "." + name + " = " + given + " is out of range; allowed: a "
				                            + E().getClassName() + " object");
			}
			v = x();
		}
		try {
			checkObjectImpl(self, name, v, 0);
		} catch (const std::exception& e) {
			throw refused(self, name, v, member, e);
		}
		setChecked(self, name, member, v);
	}
	// pySetAttr: values as boost.python converts them (validated by the postLoad after all are set),
	// objects as above.
	template <class C, class T> void setAttr(C&, const char*, T& member, const boost::python::object& value) { member = boost::python::extract<T>(value); }
	template <class C, class E> void setAttr(C& self, const char* name, shared_ptr<E>& member, const boost::python::object& value)
	{
		setObject(self, name, member, value);
	}
	// What a Python setter of an attribute of type T takes: the value itself, or any object for objects.
	template <class T> using PyValue = std::conditional_t<IsObject<T>::value, boost::python::object, T>;
	template <class C, class T> void setFromPython(C& self, const char* name, T& member, const PyValue<T>& value)
	{
		if constexpr (IsObject<T>::value) setObject(self, name, member, value);
		else
			setChecked(self, name, member, value);
	}
}
}
#define SWELLDEM_ATTR_MEMBER(type, name, def, flags, doc) type name = def;
#define SWELLDEM_ATTR_SERIALIZE(type, name, def, flags, doc)                                                                                                   \
	if (!((flags)&swelldem_attr::Transient)) ar& boost::serialization::make_nvp(#name, name);
#define SWELLDEM_ATTR_SET(type, name, def, flags, doc)                                                                                                         \
	if (key == #name) {                                                                                                                                    \
		if ((flags) & (swelldem_attr::Result | swelldem_attr::Internal))                                                                               \
			throw std::invalid_argument(getClassName() + "." #name " is a result, not a setting: it cannot be set");                            \
		swelldem_py::setAttr(*this, #name, name, value);                                                                                               \
		return;                                                                                                                                        \
	}
#define SWELLDEM_ATTR_GET(type, name, def, flags, doc)                                                                                                         \
	if (!((flags)&swelldem_attr::Internal)) ret[#name] = boost::python::object(name);
#define SWELLDEM_ATTR_PROPERTY(type, name, def, flags, doc)                                                                                                    \
	if (!((flags)&swelldem_attr::Internal)) {                                                                                                              \
		auto getter = boost::python::make_getter(&ThisClass::name, boost::python::return_value_policy<boost::python::return_by_value>());             \
		if ((flags)&swelldem_attr::Result) cls.add_property(#name, getter, "(result, read-only) " doc);                                                \
		else                                                                                                                                           \
			cls.add_property(                                                                                                                      \
			        #name, getter,                                                                                                                 \
			        +[](ThisClass& self, const swelldem_py::PyValue<type>& v) { swelldem_py::setFromPython(self, #name, self.name, v); }, doc);  \
	}
// A table of parameters stored in a plain struct member `table` (the physics core's own struct):
// #define TABLE(X) X(type, name, member path in the struct, default, "doc [unit]"); all are settings.
#define SWELLDEM_NO_TABLE(X)
#define SWELLDEM_TABLE_SERIALIZE(type, name, member, def, doc) ar& boost::serialization::make_nvp(#name, table.member);
#define SWELLDEM_TABLE_SET(type, name, member, def, doc)                                                                                                       \
	if (key == #name) {                                                                                                                                    \
		table.member = boost::python::extract<type>(value);                                                                                            \
		return;                                                                                                                                        \
	}
#define SWELLDEM_TABLE_GET(type, name, member, def, doc) ret[#name] = boost::python::object(table.member);
#define SWELLDEM_TABLE_PROPERTY(type, name, member, def, doc)                                                                                                  \
	cls.add_property(                                                                                                                                      \
	        #name, +[](const ThisClass& self) -> type { return self.table.member; },                                                                      \
	        +[](ThisClass& self, const type& v) { swelldem_py::setChecked(self, #name, self.table.member, v); }, doc);

// Everything a swelldem class needs to be a YADE Serializable. The class must also define
// `void postLoad()` (called after attributes are set from Python or loaded from a file; the
// place to validate them) and `template <class C> static void pyMethods(C&)` (extra Python methods).
#define SWELLDEM_CLASS(Class, Base, docString, ATTRS) SWELLDEM_CLASS_WITH_TABLE(Class, Base, docString, ATTRS, SWELLDEM_NO_TABLE)
#define SWELLDEM_CLASS_WITH_TABLE(Class, Base, docString, ATTRS, TABLE)                                                                                        \
public:                                                                                                                                                        \
	using ThisClass = Class;                                                                                                                               \
	ATTRS(SWELLDEM_ATTR_MEMBER)                                                                                                                            \
	string getClassName() const override { return #Class; }                                                                                                \
	string getBaseClassName(unsigned int i = 0) const override { return i == 0 ? string(#Base) : string(); }                                               \
	int    getBaseClassNumber() const override { return 1; }                                                                                               \
	void   pySetAttr(const std::string& key, const boost::python::object& value) override                                                                  \
	{                                                                                                                                                      \
		ATTRS(SWELLDEM_ATTR_SET)                                                                                                                       \
		TABLE(SWELLDEM_TABLE_SET)                                                                                                                      \
		Base::pySetAttr(key, value);                                                                                                                   \
	}                                                                                                                                                      \
	boost::python::dict pyDict() const override                                                                                                            \
	{                                                                                                                                                      \
		boost::python::dict ret;                                                                                                                       \
		ATTRS(SWELLDEM_ATTR_GET)                                                                                                                       \
		TABLE(SWELLDEM_TABLE_GET)                                                                                                                      \
		ret.update(this->pyDictCustom());                                                                                                              \
		ret.update(Base::pyDict());                                                                                                                    \
		return ret;                                                                                                                                    \
	}                                                                                                                                                      \
	void callPostLoad(void) override                                                                                                                       \
	{                                                                                                                                                      \
		Base::callPostLoad();                                                                                                                          \
		postLoad();                                                                                                                                    \
	}                                                                                                                                                      \
	void pyRegisterClass(boost::python::object scope_) override                                                                                            \
	{                                                                                                                                                      \
		checkPyClassRegistersItself(#Class);                                                                                                           \
		boost::python::scope                 thisScope(scope_);                                                                                        \
		boost::python::docstring_options     docopt;                                                                                                   \
		docopt.enable_all();                                                                                                                           \
		docopt.disable_cpp_signatures();                                                                                                               \
		boost::python::class_<Class, shared_ptr<Class>, boost::python::bases<Base>, boost::noncopyable> cls(#Class, docString);                     \
		cls.def("__init__", swelldem_py::rawConstructor(swelldem_py::constructWithAttrs<Class>));                                                       \
		ATTRS(SWELLDEM_ATTR_PROPERTY)                                                                                                                  \
		TABLE(SWELLDEM_TABLE_PROPERTY)                                                                                                                 \
		pyMethods(cls);                                                                                                                                \
	}                                                                                                                                                      \
	friend class boost::serialization::access;                                                                                                             \
	template <class Archive> void serialize(Archive& ar, unsigned int savedVersion)                                                                         \
	{                                                                                                                                                      \
		if (Archive::is_loading::value) swelldem_py::requireSceneVersion(#Class, savedVersion);                                                        \
		ar& boost::serialization::make_nvp(#Base, boost::serialization::base_object<Base>(*this));                                                     \
		ATTRS(SWELLDEM_ATTR_SERIALIZE)                                                                                                                 \
		TABLE(SWELLDEM_TABLE_SERIALIZE)                                                                                                                \
		if (Archive::is_loading::value) { /* as YADE's classes: validate and rebuild transient state on load */                                      \
			postLoad();                                                                                                                            \
			swelldem_py::afterLoad(*this);                                                                                                         \
		}                                                                                                                                              \
	}

// A class YADE dispatches on (an IPhys, a Material) needs its own index in its family.
#define SWELLDEM_CLASS_INDEX(Class, Base)                                                                                                                      \
private:                                                                                                                                                       \
	static int& indexStorage()                                                                                                                             \
	{                                                                                                                                                      \
		static int index = -1;                                                                                                                         \
		return index;                                                                                                                                  \
	}                                                                                                                                                      \
                                                                                                                                                               \
protected:                                                                                                                                                     \
	int& modifyClassIndex() override { return indexStorage(); }                                                                                            \
                                                                                                                                                               \
public:                                                                                                                                                        \
	const int& getClassIndex() const override { return indexStorage(); }                                                                                   \
	const int& getBaseClassIndex(int depth) const override                                                                                                 \
	{                                                                                                                                                      \
		static Base* base = new Base; /* leaked on purpose: no destruction-order issue at exit */                                                     \
		return depth == 1 ? base->getClassIndex() : base->getBaseClassIndex(depth - 1);                                                                \
	}

// Base-class (de)serialization must run the instances compiled into YADE's libraries (Base::serialize
// is private there): declare those instantiations extern, instantiate only their inline constructors.
#define SWELLDEM_USE_YADE_SERIALIZER(Base)                                                                                                                     \
	extern template class boost::archive::detail::oserializer<boost::archive::xml_oarchive, Base>;                                                        \
	extern template class boost::archive::detail::oserializer<boost::archive::binary_oarchive, Base>;                                                     \
	extern template class boost::archive::detail::iserializer<boost::archive::xml_iarchive, Base>;                                                        \
	extern template class boost::archive::detail::iserializer<boost::archive::binary_iarchive, Base>;

SWELLDEM_USE_YADE_SERIALIZER(yade::Serializable)
SWELLDEM_USE_YADE_SERIALIZER(yade::FrictPhys)
SWELLDEM_USE_YADE_SERIALIZER(yade::FrictMat)
SWELLDEM_USE_YADE_SERIALIZER(yade::GlobalEngine)
SWELLDEM_USE_YADE_SERIALIZER(yade::IPhysFunctor)
SWELLDEM_USE_YADE_SERIALIZER(yade::LawFunctor)

// At global scope, once per class, in its .cpp: the serialization export key and factory.
#define SWELLDEM_EXPORT_SERIALIZATION(Class)                                                                                                                   \
	BOOST_CLASS_EXPORT_KEY2(yade::Class, "yade::" #Class)                                                                                                  \
	BOOST_CLASS_EXPORT_IMPLEMENT(yade::Class)                                                                                                              \
	BOOST_SERIALIZATION_FACTORY_0(yade::Class)
