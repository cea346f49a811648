#include "features/plugin_loader.h"

#include <dlfcn.h>
#include <elf.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "features/plugin_api.h"
#include "features/python_plugins.h"
#include "util/error.h"
#include "util/file_checks.h"

namespace attend {

namespace {

// The ELF machine this attend was built for, and a name for a machine number.
#if defined(__x86_64__)
constexpr int kThisMachine = EM_X86_64;
#elif defined(__aarch64__)
constexpr int kThisMachine = EM_AARCH64;
#else
constexpr int kThisMachine = -1;  // not checked
#endif

std::string MachineName(int machine) {
  switch (machine) {
    case EM_X86_64:
      return "x86-64";
    case EM_AARCH64:
      return "AArch64 (64-bit ARM)";
    case EM_386:
      return "x86 (32-bit)";
    case EM_ARM:
      return "ARM (32-bit)";
    case EM_RISCV:
      return "RISC-V";
    case EM_PPC64:
      return "64-bit PowerPC";
    case EM_S390:
      return "IBM Z";
    default:
      return "ELF machine number " + std::to_string(machine);
  }
}

// Why the file at `path` is not a whole 64-bit ELF shared object, or "" when it is. dlopen maps
// the segments that the program headers name; a file cut short (an interrupted copy or build)
// keeps headers that point past its end, and touching those pages raises SIGBUS inside the
// dynamic loader, where no error can be caught. So every segment is checked to lie within the
// file before the library is opened.
std::string IncompleteElf(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return "cannot be read";
  file.seekg(0, std::ios::end);
  const auto size = static_cast<uint64_t>(file.tellg());
  file.seekg(0);
  Elf64_Ehdr header;
  if (size < sizeof(header) || !file.read(reinterpret_cast<char*>(&header), sizeof(header))) {
    return "is not a shared library (too short for an ELF header)";
  }
  if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0) return "is not an ELF shared library";
  if (header.e_ident[EI_CLASS] != ELFCLASS64) return "is not a 64-bit ELF library";
  if (header.e_type != ET_DYN) return "is an ELF file but not a shared library";
  // glibc's answer to a library of another machine is "cannot open shared object file: No
  // such file or directory", which reads as if the file were missing.
  if (kThisMachine >= 0 && header.e_machine != kThisMachine) {
    return "exists but cannot be loaded here: it was built for " + MachineName(header.e_machine) +
           ", and this attend runs on " + MachineName(kThisMachine) +
           "; rebuild the plugin on this machine";
  }
  // Sizes as unsigned 64-bit sums of 16- and 32-bit fields cannot overflow.
  const uint64_t table_end =
      header.e_phoff + static_cast<uint64_t>(header.e_phnum) * header.e_phentsize;
  if (header.e_phentsize != sizeof(Elf64_Phdr) || table_end > size) {
    return "is cut short or damaged (its program headers lie past the end of the file)";
  }
  // The loader does not need the section headers, but a file whose headers lie past its end
  // was cut short all the same: what else is missing cannot be told.
  const uint64_t sections_end =
      header.e_shoff + static_cast<uint64_t>(header.e_shnum) * header.e_shentsize;
  if (header.e_shoff != 0 && sections_end > size) {
    return "is cut short: it is " + std::to_string(size) +
           " bytes, but its section headers end at byte " + std::to_string(sections_end);
  }
  std::vector<Elf64_Phdr> segments(header.e_phnum);
  file.seekg(static_cast<std::streamoff>(header.e_phoff));
  if (!file.read(reinterpret_cast<char*>(segments.data()),
                 static_cast<std::streamsize>(segments.size() * sizeof(Elf64_Phdr)))) {
    return "cannot be read";
  }
  for (const Elf64_Phdr& segment : segments) {
    if (segment.p_offset > size || segment.p_filesz > size - segment.p_offset) {
      return "is cut short: it is " + std::to_string(size) + " bytes, but a segment ends at byte " +
             std::to_string(segment.p_offset + segment.p_filesz);
    }
  }
  return "";
}

}  // namespace

void LoadFeaturePlugin(const std::string& path, const std::string& where,
                       FeatureRegistry* registry) {
  const std::string prefix = where + ": plugin " + path + ": ";
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw ConfigError(prefix + "no such file");
  // A folder, a fifo or a device is named as such (dlopen or the interpreter would say "no
  // such file", or wait on a fifo).
  try {
    RequireRegularFile(path, "the plugin", ExitStatus::kUsage);
  } catch (const ConfigError& e) {
    throw ConfigError(where + ": " + e.what());
  }
  if (IsPythonPlugin(path)) {
    LoadPythonFeaturePlugin(path, where, registry);
    return;
  }
  const std::string incomplete = IncompleteElf(path);
  if (!incomplete.empty()) throw ConfigError(prefix + incomplete);
  // A relative path without a slash would make dlopen search the library path instead.
  const std::string load_path = std::filesystem::absolute(path).string();
  void* library = dlopen(load_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* error = dlerror();
    const std::string reason = error != nullptr ? error : "";
    std::string message = prefix + "cannot be loaded: " + (reason.empty() ? "unknown" : reason);
    // The plugin exists (checked above), so a missing file is one of the libraries it needs.
    if (reason.find("cannot open shared object file") != std::string::npos) {
      message += " (the plugin exists; a library it depends on was not found: check `ldd " +
                 load_path + "`)";
    }
    throw ConfigError(message);
  }
  dlerror();
  void* symbol = dlsym(library, ATTEND_PLUGIN_ENTRY_SYMBOL);
  if (symbol == nullptr) {
    dlclose(library);
    throw ConfigError(prefix + "has no '" ATTEND_PLUGIN_ENTRY_SYMBOL
                               "' entry point (define it with ATTEND_PLUGIN, "
                               "features/plugin_api.h)");
  }
  const AttendPluginInfo* info = reinterpret_cast<AttendPluginEntry>(symbol)();
  if (info == nullptr || info->register_features == nullptr) {
    dlclose(library);
    throw ConfigError(prefix + "'" ATTEND_PLUGIN_ENTRY_SYMBOL "' returned no register function");
  }
  if (info->abi_version != ATTEND_PLUGIN_ABI_VERSION) {
    const int version = info->abi_version;
    dlclose(library);
    throw ConfigError(prefix + "was built for plugin ABI version " + std::to_string(version) +
                      ", this attend has version " + std::to_string(ATTEND_PLUGIN_ABI_VERSION) +
                      "; rebuild the plugin against this attend's headers");
  }
  // The library is never closed: its features' code and vtables are used until the end.
  registry->SetOrigin(path);
  try {
    info->register_features(registry);
  } catch (const ConfigError&) {
    registry->SetOrigin("built-in");
    throw;
  } catch (const std::exception& e) {
    registry->SetOrigin("built-in");
    throw ConfigError(prefix + "failed to register its features: " + e.what());
  }
  registry->SetOrigin("built-in");
}

}  // namespace attend
