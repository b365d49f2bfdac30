// SPDX-License-Identifier: GPL-2.0-or-later
#include "SparseSolver.hpp"
#include <cstdlib>
#include <dlfcn.h>
#include <stdexcept>

namespace swelldem::linalg {

namespace {
	using OpenFn = SparseSolver* (*)(const char* name, char* error, int errorSize);

	// The module, opened once. RTLD_GLOBAL: Open MPI's components, which PETSc's MPI_Init loads,
	// look up libmpi's symbols in the global scope.
	void* moduleSymbol(const char* symbol, std::string& why)
	{
		static void*       handle = nullptr;
		static std::string failure;
		static bool        tried = false;
		if (!tried) {
			tried             = true;
			const char* env   = std::getenv("SWELLDEM_PETSC_MODULE");
			const char* where = env && *env ? env : SWELLDEM_PETSC_MODULE_PATH;
			handle            = dlopen(where, RTLD_NOW | RTLD_GLOBAL);
			if (!handle) {
				const char* e = dlerror();
				failure       = std::string("PETSc is not available: the module ") + where + " could not be loaded (" + (e ? e : "?")
				        + "); PETSc comes from Debian's petsc-dev, installed by scripts/bootstrap.sh, and the module is built with it";
			}
		}
		why = failure;
		if (!handle) return nullptr;
		void* fn = dlsym(handle, symbol);
		if (!fn) why = std::string("PETSc module without ") + symbol + ": " + SWELLDEM_PETSC_MODULE_PATH;
		return fn;
	}

	OpenFn moduleEntry(std::string& why) { return reinterpret_cast<OpenFn>(moduleSymbol("swelldem_petsc_open", why)); }

	// Under mpirun the ranks above 0 wait for rank 0's commands from their start, whether or not
	// this run uses PETSc: at exit rank 0 releases them (and finalizes MPI), however the run ended.
	void releaseRanks()
	{
		std::string why;
		if (void* fn = moduleSymbol("swelldem_petsc_release", why)) reinterpret_cast<void (*)()>(fn)();
	}
	[[maybe_unused]] const bool releaseAtExit = mpiRanks() > 1 && std::atexit(releaseRanks) == 0;
}

int mpiRanks()
{
	for (const char* name : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE" })
		if (const char* v = std::getenv(name)) {
			const int n = std::atoi(v);
			if (n > 0) return n;
		}
	return 1;
}

int runSolveWorker()
{
	std::string why;
	void*       fn = moduleSymbol("swelldem_petsc_worker", why);
	if (!fn) throw std::runtime_error(why);
	return reinterpret_cast<int (*)()>(fn)();
}

std::string petscUnavailable()
{
	std::string why;
	moduleEntry(why);
	return why;
}

std::unique_ptr<SparseSolver> openPetsc(const std::string& name)
{
	std::string why;
	OpenFn      fn = moduleEntry(why);
	if (!fn) throw std::runtime_error(why);
	char          error[512] = { 0 };
	SparseSolver* s          = fn(name.c_str(), error, int(sizeof error));
	if (!s) throw std::runtime_error(error);
	return std::unique_ptr<SparseSolver>(s);
}

} // namespace swelldem::linalg
