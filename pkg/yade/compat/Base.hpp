// SPDX-License-Identifier: GPL-2.0-or-later
// Declarations of YADE's object-model roots (Factorable, Serializable, Indexable, ClassFactory),
// written for the ABI of Debian's yade-double 2023.02a. See README.md in this folder for the rules.
#pragma once

#ifndef EIGEN_DONT_ALIGN
#error "swelldem must be compiled with -DEIGEN_DONT_VECTORIZE -DEIGEN_DONT_ALIGN -DEIGEN_DISABLE_UNALIGNED_ARRAY_ASSERT (Debian's YADE has Eigen vectorisation off)"
#endif

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <boost/enable_shared_from_this.hpp>
#include <boost/python.hpp>
#include <boost/shared_ptr.hpp>
#include <string>
#include <vector>

// YADE's singletons are a global-namespace template; instance() lives in libyade.so and must not
// be instantiated here (a second copy would be a second, empty ClassFactory).
template <class T> class Singleton {
protected:
	static T* self;

public:
	static T& instance();
};

namespace yade {
using boost::shared_ptr;
using std::string;
using std::vector;

using Real        = double;
using Vector3r    = Eigen::Matrix<Real, 3, 1>;
using Vector3i    = Eigen::Matrix<int, 3, 1>;
using Quaternionr = Eigen::Quaternion<Real>;
using Matrix3r    = Eigen::Matrix<Real, 3, 3>;
static_assert(sizeof(Real) == 8, "yade-double: Real is double");
static_assert(sizeof(Vector3r) == 24 && alignof(Vector3r) == 8, "Vector3r must be 24 bytes, 8-aligned");
static_assert(sizeof(Quaternionr) == 32 && alignof(Quaternionr) == 8, "Quaternionr must be unaligned (EIGEN_DONT_ALIGN)");

class Factorable : public boost::enable_shared_from_this<Factorable> {
public:
	Factorable() { }
	virtual ~Factorable();
	virtual string getBaseClassName(unsigned int = 0) const;
	virtual int    getBaseClassNumber() const;
	virtual string getClassName() const;
};

class ClassFactory : public Singleton<ClassFactory> {
public:
	using CreateSharedFn = shared_ptr<Factorable> (*)();
	using CreateFn       = Factorable* (*)();
	using CreatePureFn   = void* (*)();
	bool                   registerFactorable(std::string name, CreateFn create, CreateSharedFn createShared, CreatePureFn createPure);
	shared_ptr<Factorable> createShared(std::string name);
	void                   registerPluginClasses(const char* fileAndClasses[]);
	ClassFactory() = delete;
};

class Serializable : public Factorable {
public:
	Serializable() { }
	virtual ~Serializable();
	string getClassName() const override;
	string getBaseClassName(unsigned int = 0) const override;
	int    getBaseClassNumber() const override;
	// Serializable's own virtuals, in YADE's vtable order.
	virtual void                pySetAttr(const std::string& key, const boost::python::object& value);
	virtual boost::python::dict pyDict() const;
	virtual boost::python::dict pyDictCustom() const;
	virtual void                callPostLoad(void);
	virtual void                checkPyClassRegistersItself(const std::string& thisClassName) const;
	virtual void                pyRegisterClass(boost::python::object _scope);
	virtual void                pyHandleCustomCtorArgs(boost::python::tuple& args, boost::python::dict& kw);
	void                        pyUpdateAttrs(const boost::python::dict& d);
};

// Multimethod dispatch index. The per-family counters live in YADE's libraries: they are only
// declared here so that every plugin class draws its index from YADE's own counter.
class Indexable {
protected:
	void createIndex()
	{
		int& index = modifyClassIndex();
		if (index == -1) {
			index = getMaxCurrentlyUsedClassIndexOfKin() + 1;
			incrementMaxCurrentlyUsedClassIndexOfKin();
		}
	}
	virtual void incrementMaxCurrentlyUsedClassIndexOfKin();
	virtual int& modifyClassIndex();

public:
	Indexable() { }
	virtual ~Indexable() { } // inline in YADE, hence not exported: defined here
	virtual const int& getClassIndex() const;
	virtual const int& getBaseClassIndex(int) const;
	virtual const int& getMaxCurrentlyUsedClassIndexOfKin() const;
};

struct TimingInfo {
	long               nExec;
	unsigned long long nsec;
};
class TimingDeltas;

} // namespace yade

// The overrides every YADE Serializable subclass declares (defined in YADE's libraries for YADE's
// classes, so only declared here).
#define SWELLDEM_COMPAT_SERIALIZABLE_DECLS                                                                                                                     \
	string              getClassName() const override;                                                                                                     \
	string              getBaseClassName(unsigned int = 0) const override;                                                                                 \
	int                 getBaseClassNumber() const override;                                                                                               \
	void                pySetAttr(const std::string& key, const boost::python::object& value) override;                                                    \
	boost::python::dict pyDict() const override;                                                                                                           \
	void                callPostLoad(void) override;                                                                                                       \
	void                pyRegisterClass(boost::python::object _scope) override;

// The index overrides of a YADE class that is itself dispatched on (REGISTER_CLASS_INDEX).
#define SWELLDEM_COMPAT_INDEX_DECLS                                                                                                                            \
protected:                                                                                                                                                     \
	int& modifyClassIndex() override;                                                                                                                      \
                                                                                                                                                               \
public:                                                                                                                                                        \
	const int& getClassIndex() const override;                                                                                                             \
	const int& getBaseClassIndex(int) const override;

// The index counter of a dispatch family root (IPhys, IGeom, Material, ...): five new slots.
#define SWELLDEM_COMPAT_INDEX_COUNTER_DECLS                                                                                                                    \
protected:                                                                                                                                                     \
	int& modifyClassIndex() override;                                                                                                                      \
                                                                                                                                                               \
public:                                                                                                                                                        \
	const int& getClassIndex() const override;                                                                                                             \
	const int& getBaseClassIndex(int) const override;                                                                                                      \
	const int& getMaxCurrentlyUsedClassIndexOfKin() const override;                                                                                        \
                                                                                                                                                               \
protected:                                                                                                                                                     \
	void incrementMaxCurrentlyUsedClassIndexOfKin() override;                                                                                              \
                                                                                                                                                               \
public:
