#include "apps/brdfrig/board_options.h"

#include "common/atomic_file.h"
#include "common/json_parse.h"

namespace brdfrig::apps {

void AddBoardOptions(CLI::App* cmd, BoardArgs& args, bool with_file) {
  if (with_file) {
    cmd->add_option("--board", args.board_file,
                    "targets.json written by `brdfrig target print` (the board's geometry)");
  }
  cmd->add_option("--squares", args.squares, "Chessboard squares across and down (default 11 8)")
      ->expected(2);
  cmd->add_option("--square-mm", args.square_mm, "Side of a square in mm (default 20)");
  cmd->add_option("--marker-mm", args.marker_mm, "Side of a marker in mm (default 15)");
  cmd->add_option("--dictionary", args.dictionary, "ArUco dictionary (default DICT_5X5_100)");
  cmd->add_option("--page-mm", args.page_mm, "Page width and height in mm (default 297 210)")
      ->expected(2);
}

calibrate::CharucoSpec BoardSpecFrom(const BoardArgs& args) {
  calibrate::CharucoSpec spec;
  if (!args.board_file.empty()) {
    const nlohmann::json j = ParseJson(ReadFileToString(args.board_file), args.board_file);
    spec =
        calibrate::CharucoSpec::FromJson(j.contains("board") ? j.at("board") : j, args.board_file);
  }
  if (args.squares.size() == 2) {
    spec.squares_x = args.squares[0];
    spec.squares_y = args.squares[1];
  }
  if (args.square_mm > 0) spec.square_m = 1e-3 * args.square_mm;
  if (args.marker_mm > 0) spec.marker_m = 1e-3 * args.marker_mm;
  if (!args.dictionary.empty()) spec.dictionary = args.dictionary;
  if (args.page_mm.size() == 2) {
    spec.page_width_m = 1e-3 * args.page_mm[0];
    spec.page_height_m = 1e-3 * args.page_mm[1];
  }
  spec.Validate();
  return spec;
}

}  // namespace brdfrig::apps
