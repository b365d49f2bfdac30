// SPDX-License-Identifier: GPL-2.0-or-later
#include "YadeBuildCheck.hpp"

#include <elf.h>
#include <link.h>

#include <cstring>
#include <map>
#include <sstream>

namespace swelldem_compat {
namespace {

	struct LoadedIds {
		std::map<std::string, std::pair<std::string, std::string>> byName; // basename -> (path, build id)
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

	// The build id is read from the loaded image's PT_NOTE segments, not from the file on disk:
	// what matters is the code in this process, whatever the file now holds.
	int collect(struct dl_phdr_info* info, size_t, void* data)
	{
		auto* ids = static_cast<LoadedIds*>(data);
		const std::string path = info->dlpi_name ? info->dlpi_name : "";
		const std::string base = path.substr(path.find_last_of('/') + 1);
		if (base.empty()) return 0;
		for (int i = 0; i < info->dlpi_phnum; ++i) {
			const ElfW(Phdr)& ph = info->dlpi_phdr[i];
			if (ph.p_type != PT_NOTE) continue;
			auto*       p   = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
			const auto* end = p + ph.p_memsz;
			while (p + sizeof(ElfW(Nhdr)) <= end) {
				const auto* nh   = reinterpret_cast<const ElfW(Nhdr)*>(p);
				const auto* name = p + sizeof(ElfW(Nhdr));
				const auto* desc = name + ((nh->n_namesz + 3) & ~3u);
				if (desc + nh->n_descsz > end) break;
				if (nh->n_type == NT_GNU_BUILD_ID && nh->n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0)
					ids->byName[base] = { path, hex(desc, nh->n_descsz) };
				p = desc + ((nh->n_descsz + 3) & ~3u);
			}
		}
		return 0;
	}

} // namespace

std::string yadeBuildMismatch(const char* expectedIds)
{
	LoadedIds loaded;
	dl_iterate_phdr(collect, &loaded);
	std::ostringstream why;
	std::stringstream  list(expectedIds ? expectedIds : "");
	std::string        item;
	while (std::getline(list, item, ',')) {
		const auto colon = item.find(':');
		if (colon == std::string::npos) continue;
		const std::string lib = item.substr(0, colon), want = item.substr(colon + 1);
		const auto        it  = loaded.byName.find(lib);
		if (it == loaded.byName.end())
			why << lib << " (build id " << want << ") is not loaded in this process; ";
		else if (it->second.second != want)
			why << it->second.first << " has build id " << it->second.second << ", the plugin was built against build id " << want
			    << "; ";
	}
	return why.str();
}

} // namespace swelldem_compat
