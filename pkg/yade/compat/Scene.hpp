// SPDX-License-Identifier: GPL-2.0-or-later
// Declarations of the YADE scene objects swelldem reads or derives from: interaction physics and
// geometry, body state, materials, bodies, interactions, containers and the Scene itself.
// Data members are declared in YADE's order with YADE's types; byte offsets are listed in
// README.md and checked at test time (tests/python/test_abi_layout.py).
#pragma once
#include "Base.hpp"
#include <map>
#include <mutex>

namespace yade {
class Scene;
class Interaction;
class Body;
class State;

/* ------------------------------------------------------------------ interaction physics */
class IPhys : public Serializable, public Indexable {
public:
	virtual ~IPhys();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	SWELLDEM_COMPAT_INDEX_COUNTER_DECLS
};

class NormPhys : public IPhys {
public:
	NormPhys();
	virtual ~NormPhys();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Real     kn;          // @32
	Vector3r normalForce; // @40
	SWELLDEM_COMPAT_INDEX_DECLS
};

class NormShearPhys : public NormPhys {
public:
	NormShearPhys();
	virtual ~NormShearPhys();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Real     ks;         // @64
	Vector3r shearForce; // @72
	SWELLDEM_COMPAT_INDEX_DECLS
};

class FrictPhys : public NormShearPhys {
public:
	FrictPhys();
	virtual ~FrictPhys();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Real tangensOfFrictionAngle; // @96; sizeof 104
	SWELLDEM_COMPAT_INDEX_DECLS
};

/* ------------------------------------------------------------------ interaction geometry */
class IGeom : public Serializable, public Indexable {
public:
	virtual ~IGeom();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	SWELLDEM_COMPAT_INDEX_COUNTER_DECLS
};

class GenericSpheresContact : public IGeom {
public:
	virtual ~GenericSpheresContact();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Vector3r normal;       // @32
	Vector3r contactPoint; // @56
	Real     refR1;        // @80
	Real     refR2;        // @88
	SWELLDEM_COMPAT_INDEX_DECLS
};

// Only read, never constructed by swelldem.
class ScGeom : public GenericSpheresContact {
	Vector3r twist_axis;       // @96
	Vector3r orthonormal_axis; // @120

public:
	Real& radius1; // @144
	Real& radius2; // @152
	ScGeom() = delete;
	virtual ~ScGeom();
	// Carries a shear vector over to the current contact plane (exported by libpkg_dem.so).
	Vector3r&       rotate(Vector3r& tangentVector) const;
	const Vector3r& shearIncrement() const { return shearInc; }
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Real     penetrationDepth; // @160, positive when the spheres overlap
	Vector3r shearInc;         // @168; sizeof 192
	SWELLDEM_COMPAT_INDEX_DECLS
};

/* ------------------------------------------------------------------ state, material, body */
template <class Scalar> struct Se3 {
	Eigen::Matrix<Scalar, 3, 1> position;
	Eigen::Quaternion<Scalar>   orientation;
};
using Se3r = Se3<Real>;

class State : public Serializable, public Indexable {
public:
	State() = delete;
	virtual ~State();
	Vector3r&    pos; // @32, refers to se3.position
	Quaternionr& ori; // @40
	std::mutex   updateMutex;
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Se3r        se3;            // @88
	Vector3r    vel;            // @144
	Real        mass;           // @168
	Vector3r    angVel;         // @176
	Vector3r    angMom;         // @200
	Vector3r    inertia;        // @224
	Vector3r    refPos;         // @248
	Quaternionr refOri;         // @272
	unsigned    blockedDOFs;    // @304, bits x y z X Y Z = 1 2 4 8 16 32
	bool        isDamped;       // @308
	Real        densityScaling; // @312; sizeof 320
	SWELLDEM_COMPAT_INDEX_COUNTER_DECLS
	enum { DOF_X = 1, DOF_Y = 2, DOF_Z = 4, DOF_RX = 8, DOF_RY = 16, DOF_RZ = 32 };
};

class Material : public Serializable, public Indexable {
public:
	Material() = delete;
	virtual ~Material();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	virtual shared_ptr<State> newAssocState() const;
	virtual bool              stateTypeOk(State*) const;
	int                       id;      // @32
	string                    label;   // @40
	Real                      density; // @72
	SWELLDEM_COMPAT_INDEX_COUNTER_DECLS
};

class ElastMat : public Material {
public:
	ElastMat();
	virtual ~ElastMat();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Real young;   // @80
	Real poisson; // @88
	SWELLDEM_COMPAT_INDEX_DECLS
};

class FrictMat : public ElastMat {
public:
	FrictMat();
	virtual ~FrictMat();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	Real frictionAngle; // @96; sizeof 104
	SWELLDEM_COMPAT_INDEX_DECLS
};

class Body : public Serializable {
public:
	using id_t        = int;
	using MapId2IntrT = std::map<id_t, shared_ptr<Interaction>>;
	static const shared_ptr<Body>& byId(id_t _id, Scene* rb = nullptr); // exported
	Body() = delete;
	virtual ~Body();
	virtual void userForcedDisplacementRedrawHook();
	SWELLDEM_COMPAT_SERIALIZABLE_DECLS
	id_t                   id;        // @24
	int                    groupMask; // @28
	int                    flags;     // @32
	int                    subdomain; // @36 (MPI feature)
	shared_ptr<Material>   material;  // @40
	shared_ptr<State>      state;     // @56
	shared_ptr<Factorable> shape;     // @72
	shared_ptr<Factorable> bound;     // @88
	MapId2IntrT            intrs;     // @104
	id_t                   clumpId;   // @152
	long                   iterBorn;  // @160
	Real                   timeBorn;  // @168; sizeof 176
	bool                   isClump() const { return clumpId != -1 && id == clumpId; }
	bool                   isClumpMember() const { return clumpId != -1 && id != clumpId; }
};

class BodyContainer : public Serializable {
public:
	BodyContainer() = delete;
	size_t                        size() const;                // exported
	shared_ptr<Body>&             operator[](unsigned int id); // exported
	std::vector<shared_ptr<Body>> body;                        // @24
};

/* ------------------------------------------------------------------ interactions */
class IGeomFunctor;
class IPhysFunctor;
class LawFunctor;

class Interaction : public Serializable {
public:
	Interaction() = delete;
	bool isActive; // @24
	struct {
		bool                     geomExists;
		shared_ptr<IGeomFunctor> geom;
		shared_ptr<IPhysFunctor> phys;
		shared_ptr<LawFunctor>   constLaw;
	} functorCache; // @32
	const Body::id_t& getId1() const { return id1; }
	const Body::id_t& getId2() const { return id2; }
	bool              isReal() const { return (bool)geom && (bool)phys; }
	Body::id_t        id1;          // @88
	Body::id_t        id2;          // @92
	long              iterMadeReal; // @96
	long              iterLastSeen; // @104
	shared_ptr<IGeom> geom;         // @112
	shared_ptr<IPhys> phys;         // @128
	Vector3i          cellDist;     // @144
	int               linIx;        // @156
	long              iterBorn;     // @160; sizeof 168
};

// Only the leading members are declared: swelldem reads the linear interaction list.
class InteractionContainer : public Serializable {
public:
	InteractionContainer() = delete;
	std::vector<shared_ptr<Interaction>> linIntrs;    // @24
	std::vector<shared_ptr<Interaction>> sortedIntrs; // @48
	const void*                          bodies;      // @72
	size_t                               currSize;    // @80
	void requestErase(Interaction* I);                // exported
	const shared_ptr<Interaction>& find(Body::id_t id1, Body::id_t id2); // exported
};

/* ------------------------------------------------------------------ forces and scene */
// The OpenMP flavour of YADE's force container; swelldem uses only its exported methods.
class ForceContainer {
	using vvector = std::vector<Vector3r>;
	std::vector<vvector>    _forceData;
	std::vector<vvector>    _torqueData;
	std::vector<Body::id_t> _maxId;
	std::vector<size_t>     sizeOfThreads;
	vvector                 _force, _torque, _permForce, _permTorque;
	size_t                  size;
	bool                    syncedSizes;
	int                     nThreads;
	bool                    permForceUsed;
	bool                    permForceSynced;
	std::mutex              globalMutex;
	const Vector3r          _zero;

public:
	bool          synced;
	unsigned long syncCount;
	long          lastReset; // sizeof 304
	ForceContainer() = delete;
	void            addForce(Body::id_t id, const Vector3r& f);
	void            addTorque(Body::id_t id, const Vector3r& t);
	const Vector3r& getForce(Body::id_t id);
	const Vector3r& getTorque(Body::id_t id);
	void            sync();
};

class Engine;
class Scene : public Serializable {
	const unsigned int hostNameMax = 255;

public:
	Scene() = delete;
	ForceContainer                   forces; // @32
	Eigen::Matrix<Real, 10, 1>       SpeedElements;
	shared_ptr<Factorable>           renderer; // OpenGL feature
	int64_t                          prevTime;
	Real                             dt;   // @440
	long                             iter; // @448
	bool                             subStepping;
	int                              subStep;
	Real                             time; // @464
	Real                             speed;
	long                             stopAtIter;
	Real                             stopAtTime;
	bool                             isPeriodic; // @496
	bool                             trackEnergy;
	bool                             doSort;
	bool                             runInternalConsistencyChecks;
	Body::id_t                       selectedBody;
	int                              subdomain; // MPI feature
	shared_ptr<Factorable>           subD;      // MPI feature
	vector<string>                   tags;
	vector<shared_ptr<Engine>>       engines;
	vector<shared_ptr<Engine>>       _nextEngines;
	shared_ptr<BodyContainer>        bodies;       // @600
	shared_ptr<InteractionContainer> interactions; // @616
	shared_ptr<Factorable>           energy;
	vector<shared_ptr<Material>>     materials; // @648
	shared_ptr<Factorable>           bound;
	shared_ptr<Factorable>           cell; // @688
	vector<shared_ptr<Serializable>> miscParams;
	vector<shared_ptr<Factorable>>   dispParams; // sizeof 752
};

} // namespace yade
