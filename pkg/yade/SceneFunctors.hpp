// SPDX-License-Identifier: GPL-2.0-or-later
// The functors of one type in a dispatcher of the scene's InteractionLoops, for the solvers' checks
// and for reaching the law functor that owns the run's laws.
#pragma once
#include "compat/Plugin.hpp"
#include <vector>

namespace yade {

/// The functors of type F in the dispatcher `dispatcher` ("physDispatcher", "lawDispatcher") of
/// every engine that has one, found through YADE's Python interface (the dispatchers' layout is not
/// declared in compat/). Raw pointers, valid while the scene's engines are: a shared_ptr extracted
/// from Python owns a reference to a Python object and must not outlive the GIL held here (released
/// later, it can free that object without the GIL and abort). Engines that cannot be read are skipped.
template <class F> std::vector<F*> sceneFunctors(Scene* scene, const char* dispatcher)
{
	namespace bp = boost::python;
	std::vector<F*>  found;
	PyGILState_STATE gil = PyGILState_Ensure();
	try {
		for (const auto& e : scene->engines) {
			if (!e) continue;
			bp::object engine(e);
			if (!PyObject_HasAttrString(engine.ptr(), dispatcher)) continue;
			bp::object functors = engine.attr(dispatcher).attr("functors");
			for (long i = 0; i < bp::len(functors); ++i) {
				bp::extract<shared_ptr<F>> f(functors[i]);
				if (f.check()) found.push_back(f().get());
			}
		}
	} catch (const bp::error_already_set&) {
		PyErr_Clear();
	}
	PyGILState_Release(gil);
	return found;
}

} // namespace yade
