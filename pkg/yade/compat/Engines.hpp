// SPDX-License-Identifier: GPL-2.0-or-later
// Declarations of YADE's engines and dispatched functors (Engine, GlobalEngine, Functor2D,
// IPhysFunctor, LawFunctor). Constructors that YADE inlines (and so does not export) are
// defined here; everything YADE exports is only declared.
#pragma once
#include "Scene.hpp"
#include <boost/mpl/at.hpp>
#include <boost/mpl/vector.hpp>

namespace yade {

class Engine : public Serializable {
public:
	Scene*                   scene;        // @24
	TimingInfo               timingInfo;   // @32
	shared_ptr<TimingDeltas> timingDeltas; // @48
	Engine();                              // exported: binds the engine to Omega's current scene
	virtual ~Engine();
	virtual bool isActivated();
	virtual void action();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	bool   dead;       // @64
	int    ompThreads; // @68
	string label;      // @72; sizeof 104
};

class GlobalEngine : public Engine {
public:
	GlobalEngine()
	        : Engine()
	{
	}
	virtual ~GlobalEngine();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
};

// The dispatch entry points of a functor: one go()/goReverse() per arity; the unused arities take
// mpl_::void_ parameters, exactly as YADE's template expands them.
template <class ResultType, class ArgumentTypeList> class FunctorWrapper {
	using P1 = typename boost::mpl::at_c<ArgumentTypeList, 0>::type;
	using P2 = typename boost::mpl::at_c<ArgumentTypeList, 1>::type;
	using P3 = typename boost::mpl::at_c<ArgumentTypeList, 2>::type;
	using P4 = typename boost::mpl::at_c<ArgumentTypeList, 3>::type;
	using P5 = typename boost::mpl::at_c<ArgumentTypeList, 4>::type;
	using P6 = typename boost::mpl::at_c<ArgumentTypeList, 5>::type;
	using P7 = typename boost::mpl::at_c<ArgumentTypeList, 6>::type;

public:
	FunctorWrapper() { }
	virtual ~FunctorWrapper() { } // inline in YADE, hence not exported: defined here
	virtual string     checkOrder() const;
	virtual ResultType go(P1);
	virtual ResultType go(P1, P2);
	virtual ResultType go(P1, P2, P3);
	virtual ResultType go(P1, P2, P3, P4);
	virtual ResultType go(P1, P2, P3, P4, P5);
	virtual ResultType go(P1, P2, P3, P4, P5, P6);
	virtual ResultType go(P1, P2, P3, P4, P5, P6, P7);
	virtual ResultType goReverse(P1);
	virtual ResultType goReverse(P1, P2);
	virtual ResultType goReverse(P1, P2, P3);
	virtual ResultType goReverse(P1, P2, P3, P4);
	virtual ResultType goReverse(P1, P2, P3, P4, P5);
	virtual ResultType goReverse(P1, P2, P3, P4, P5, P6);
	virtual ResultType goReverse(P1, P2, P3, P4, P5, P6, P7);
};

class Functor : public Serializable {
public:
	virtual vector<std::string> getFunctorTypes() const;
	shared_ptr<TimingDeltas>    timingDeltas; // @24
	Scene*                      scene;        // @40
	Functor()
	        : scene(nullptr)
	{
	}
	virtual ~Functor();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	string label; // @48; sizeof 80
};

template <class D1, class D2, class R, class Args> class Functor2D : public Functor, public FunctorWrapper<R, Args> {
public:
	using DispatchType1 = D1;
	using DispatchType2 = D2;
	using ReturnType    = R;
	using ArgumentTypes = Args;
	Functor2D() { }
	virtual ~Functor2D();
	virtual std::string get2DFunctorType1(void) const;
	virtual std::string get2DFunctorType2(void) const;
	vector<string>      getFunctorTypes() const override;
	string              getClassName() const override;
	string              getBaseClassName(unsigned int = 0) const override;
	int                 getBaseClassNumber() const override;
};

class IPhysFunctor : public Functor2D<Material, Material, void,
                                      boost::mpl::vector<const shared_ptr<Material>&, const shared_ptr<Material>&, const shared_ptr<Interaction>&>> {
public:
	IPhysFunctor() { }
	virtual ~IPhysFunctor();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
};

class LawFunctor : public Functor2D<IGeom, IPhys, bool, boost::mpl::vector<shared_ptr<IGeom>&, shared_ptr<IPhys>&, Interaction*>> {
public:
	LawFunctor() { }
	virtual ~LawFunctor();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
};

} // namespace yade
