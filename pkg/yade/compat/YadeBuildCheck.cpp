// SPDX-License-Identifier: GPL-2.0-or-later
#include "YadeBuildCheck.hpp"

#include <elf.h>
#include <link.h>

#include <climits>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

namespace swelldem_compat {
namespace {

	struct Image {
		std::string path, base, soname, buildId;
	};

	std::string hex(const unsigned char* p, size_t n)
	{
		static const char* digits = "0123456789abcdef";
		std::string s;
		for (size_t i = 0; i < n; ++i) {
			s += digits[p[i] >> 4];
			s += digits[p[i] & 15];
		}
		return s;
	}

	// The build id and SONAME are read from the mapped image (its PT_NOTE and PT_DYNAMIC segments),
	// not from the file on disk: what matters is the code in this process, whatever the file now
	// holds or is called.
	int collect(struct dl_phdr_info* info, size_t, void* data)
	{
		auto*       images = static_cast<std::vector<Image>*>(data);
		Image       im;
		im.path = info->dlpi_name ? info->dlpi_name : "";
		if (im.path.empty()) return 0; // the executable
		im.base = im.path.substr(im.path.find_last_of('/') + 1);
		for (int i = 0; i < info->dlpi_phnum; ++i) {
			const ElfW(Phdr)& ph = info->dlpi_phdr[i];
			if (ph.p_type == PT_NOTE) {
				auto*       p   = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
				const auto* end = p + ph.p_memsz;
				while (p + sizeof(ElfW(Nhdr)) <= end) {
					const auto* nh   = reinterpret_cast<const ElfW(Nhdr)*>(p);
					const auto* name = p + sizeof(ElfW(Nhdr));
					const auto* desc = name + ((nh->n_namesz + 3) & ~3u);
					if (desc + nh->n_descsz > end) break;
					if (nh->n_type == NT_GNU_BUILD_ID && nh->n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0)
						im.buildId = hex(desc, nh->n_descsz);
					p = desc + ((nh->n_descsz + 3) & ~3u);
				}
			} else if (ph.p_type == PT_DYNAMIC) {
				const auto* dyn     = reinterpret_cast<const ElfW(Dyn)*>(info->dlpi_addr + ph.p_vaddr);
				ElfW(Addr)  strtab  = 0;
				long        soname  = -1;
				for (; dyn->d_tag != DT_NULL; ++dyn) {
					if (dyn->d_tag == DT_STRTAB) strtab = dyn->d_un.d_ptr;
					if (dyn->d_tag == DT_SONAME) soname = long(dyn->d_un.d_val);
				}
				// glibc relocates DT_STRTAB in place on x86-64; an unrelocated one is an offset from the base.
				if (strtab && strtab < info->dlpi_addr) strtab += info->dlpi_addr;
				if (strtab && soname >= 0) im.soname = reinterpret_cast<const char*>(strtab + soname);
			}
		}
		images->push_back(im);
		return 0;
	}

	std::string shownPath(const std::string& path)
	{
		char real[PATH_MAX];
		return realpath(path.c_str(), real) && path != real ? path + " -> " + real : path;
	}

} // namespace

YadeBuildProblem yadeBuildMismatch(const char* expectedIds)
{
	std::vector<Image> images;
	dl_iterate_phdr(collect, &images);
	YadeBuildProblem   out;
	std::ostringstream why;
	std::stringstream  list(expectedIds ? expectedIds : "");
	std::string        item;
	while (std::getline(list, item, ',')) {
		const auto colon = item.find(':');
		if (colon == std::string::npos) continue;
		const std::string  lib = item.substr(0, colon), want = item.substr(colon + 1);
		std::vector<Image> copies;
		for (const Image& im : images)
			if (im.soname == lib || im.base == lib || im.buildId == want) copies.push_back(im);
		if (copies.empty()) {
			why << lib << " (build id " << want << ") is not loaded in this process; ";
			continue;
		}
		if (copies.size() > 1) {
			out.twoCopies = true;
			why << copies.size() << " copies of " << lib << " are mapped: ";
			for (size_t i = 0; i < copies.size(); ++i)
				why << (i ? ", " : "") << shownPath(copies[i].path) << " (build id " << (copies[i].buildId.empty() ? "none" : copies[i].buildId) << ")";
			why << "; ";
		}
		for (const Image& im : copies)
			if (im.buildId != want)
				why << shownPath(im.path) << " has build id " << (im.buildId.empty() ? "none" : im.buildId)
				    << ", the plugin was built against build id " << want << "; ";
	}
	out.why = why.str();
	return out;
}

} // namespace swelldem_compat
