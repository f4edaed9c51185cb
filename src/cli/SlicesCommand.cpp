// `cloudlut slices PATH --out FILE.png`: a contact sheet of a table's slices, to see at a
// glance what a table holds and spot seams, NaNs and banding.
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/Command.h"
#include "io/ContactSheet.h"
#include "cli/Options.h"
#include "core/Errors.h"
#include "io/LutIo.h"
#include "io/PngImage.h"

namespace cloudlut::cli {
namespace {

int runSlices(int argc, char** argv) {
  cxxopts::Options options("cloudlut slices", "Draw a contact sheet of a table's slices as a PNG.");
  options.add_options()
    ("path", "LUT directory or table file", cxxopts::value<std::string>())
    ("table", "table name, when PATH is a directory (default: the first)", cxxopts::value<std::string>())
    ("channel", "channel index", cxxopts::value<int>()->default_value("0"))
    ("range", "colour-scale range lo,hi (default: the channel's min,max)", cxxopts::value<std::string>())
    ("out", "output PNG", cxxopts::value<std::string>());
  options.parse_positional({"path"});
  options.positional_help("PATH");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("path")) throw UsageError("missing PATH (a LUT directory or table file)");
  if (!args.count("out")) throw UsageError("missing --out FILE.png");
  const std::filesystem::path path = args["path"].as<std::string>(), out = args["out"].as<std::string>();
  if (out.extension() != ".png") throw UsageError("--out must name a .png file");

  io::ContactSheetOptions opts;
  opts.channel = args["channel"].as<int>();
  if (args.count("range")) opts.range = parseRangeOption(args["range"].as<std::string>(), "range");

  Table4D table;
  std::string title;
  if (std::filesystem::is_directory(path)) {
    const io::LutSet set = io::readLutSet(path);
    if (set.tables.empty()) throw FileError(path.string(), "the manifest lists no tables");
    std::string name = args.count("table") ? args["table"].as<std::string>() : set.tables.begin()->first;
    const auto it = set.tables.find(name);
    if (it == set.tables.end()) throw UsageError("--table: no table '" + name + "' in " + path.string());
    table = it->second.table;
    title = name;
  } else {
    table = io::readLut(path).table;
    title = table.name();
  }
  const io::RgbImage sheet = io::drawContactSheet(table, title, opts);
  io::writePng(out, sheet.width, sheet.height, sheet.rgb);
  std::printf("wrote %s (%dx%d)\n", out.c_str(), sheet.width, sheet.height);
  return kExitOk;
}

const CommandRegistration registration{"slices", "draw a contact sheet of a table's slices (PNG)", runSlices};

}  // namespace
}  // namespace cloudlut::cli
