#pragma once
/// Loading a shared module (dlopen) the first time a feature needs it, so that the heavy
/// libraries behind rarely used formats (OpenImageIO, OpenVDB) are not loaded by every process.

#include <string>

namespace nenrin {

/// The address of `symbol` in the module `fileName` (e.g. "libnenrin_vdb_writer.so"), looked for
/// in $NENRIN_MODULE_DIR, at `builtPath` (where the build put it) and beside the running binary.
/// Opened once per process. Throws InputError naming `feature` and every place tried.
void* moduleSymbol(const std::string& fileName, const std::string& builtPath, const char* symbol,
                   const std::string& feature);

}  // namespace nenrin
