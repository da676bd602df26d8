// Output directories of the `gphr` commands, created collectively: rank 0 acts, and its failure
// is thrown on every rank (a rank that threw alone would leave the others waiting in the next
// collective).
#include <Teuchos_CommHelpers.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "gphr/core/Error.hpp"
#include "gphr/driver/OutputDirectory.hpp"

namespace gphr {


void writeTextFile(const std::string& path, const std::string& text) {
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    GPHR_REQUIRE(out.good(), InputError, "cannot write '", temp, "': ", std::strerror(errno));
    out << text;
    out.close();
    if (out.fail()) {  // a full disk, say: no empty or short temporary file is left behind
      const std::string why = std::strerror(errno);
      std::remove(temp.c_str());
      throw InputError(detail::concat("cannot write '", temp, "' (", text.size(), " bytes): ", why));
    }
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(temp.c_str());
    throw InputError(detail::concat("cannot rename '", temp, "' to '", path, "': ", why));
  }
}

void finishText(std::ofstream& os, const std::string& path) {
  const bool opened = os.is_open();
  if (opened) os.close();
  GPHR_REQUIRE(opened && !os.fail(), InputError, "cannot write '", path, "': ", std::strerror(errno));
}

void agreeOnError(const RCP<const Comm>& comm, std::string error) {
  int length = comm->getRank() == 0 ? static_cast<int>(error.size()) : 0;
  Teuchos::broadcast(*comm, 0, Teuchos::outArg(length));
  error.resize(static_cast<size_t>(length));
  if (length > 0) Teuchos::broadcast(*comm, 0, length, error.data());
  GPHR_REQUIRE(length == 0, InputError, error);
}

void onRootAgreed(const RCP<const Comm>& comm, const std::string& what, const std::function<void()>& work) {
  std::string error;
  if (comm->getRank() == 0) {
    try {
      work();
    } catch (const InputError& e) {
      error = detail::concat(what, ": ", e.what());
    }
  }
  agreeOnError(comm, error);
}

namespace {
std::filesystem::path resolved(const std::string& p) {
  std::error_code ec;
  const auto abs = std::filesystem::absolute(p, ec).lexically_normal();
  const auto out = std::filesystem::weakly_canonical(abs, ec);
  return ec ? abs : out;
}

// Whether `inner` is `outer` or lies below it (whole path components).
bool within(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty() && std::next(o) == outer.end()) break;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}
}  // namespace

void requireOutputsApart(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (const auto& out : outputs) {
    const auto o = resolved(out.path);
    for (const auto& in : inputs) {
      const auto i = resolved(in.path);
      GPHR_REQUIRE(!within(i, o), InputError, out.what, " '", out.path, "' ", i == o ? "is" : "contains", " ", in.what,
                   " '", in.path, "', which the command reads; allowed: an output apart from its inputs (it would be "
                   "overwritten)");
    }
  }
}

void requireWritableBeside(const std::string& path, const std::string& what, const RCP<const Comm>& comm) {
  std::string error;
  if (comm->getRank() == 0) {
    std::error_code ec;
    auto dir = std::filesystem::path(path).parent_path();
    if (dir.empty()) dir = ".";
    std::filesystem::create_directories(dir, ec);
    const std::string probe = (dir / ("." + std::filesystem::path(path).filename().string() + ".writable")).string();
    std::FILE* f = ec ? nullptr : std::fopen(probe.c_str(), "w");
    if (!f) {
      error = detail::concat("cannot write ", what, " '", path, "': ", ec ? ec.message() : std::strerror(errno),
                             " (checked before any work)");
    } else {
      std::fclose(f);
      std::remove(probe.c_str());
    }
  }
  agreeOnError(comm, error);
}

void makeDirectory(const std::string& dir, const RCP<const Comm>& comm) {
  std::string error;
  if (comm->getRank() == 0) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) error = detail::concat("cannot create directory '", dir, "': ", ec.message());
  }
  agreeOnError(comm, error);
}

void prepareOutputDir(RunContext& ctx, bool removeSummary) {
  std::string error;
  if (ctx.comm->getRank() == 0) {
    std::error_code ec;
    std::filesystem::create_directories(ctx.outputDir, ec);
    if (ec) error = detail::concat("cannot create output directory '", ctx.outputDir, "': ", ec.message());
    const std::string earlier = ctx.outputDir + "/summary.json";
    if (removeSummary && error.empty() && std::filesystem::exists(earlier, ec)) {
      ctx.replacesEarlierRun = true;
      if (!std::filesystem::remove(earlier, ec) || ec)
        error = detail::concat("cannot remove the earlier run's '", earlier, "': ", ec.message());
    }
  }
  agreeOnError(ctx.comm, error);
}

}  // namespace gphr
