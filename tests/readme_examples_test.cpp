// The README's examples stay true: every indented example block whose first line is a `planet`
// command (optionally behind a `printf ... |` pipe) and that shows the command's output below it
// is run with the built `planet`, in a fresh folder of its own, and must print what the README
// shows. Blocks with only a command (no output lines) are not run.
//
// What is compared: standard output, then standard error, line by line against the lines below
// the command (the examples print on one of the two only, so no interleaving is lost). Lines
// that report timings or throughput (a number of seconds, "thousand a second", "threads") differ
// from run to run and machine to machine: in those, on both sides, every number is replaced by a
// wildcard before comparing (so their words and layout are checked, their figures are not).
// Every other line must match exactly.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace planet::test {
namespace {

struct Example {
  int line = 0;  // of the command in README.md, from 1
  std::string command;
  std::vector<std::string> output;
};

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool isBlank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

size_t indentOf(const std::string& line) { return line.find_first_not_of(' '); }

// `planet ...`, or `printf ... | planet ...`.
const std::regex kCommand(R"(^(printf .* \| )?planet( .*)?$)");

// Indented blocks (4 spaces or more, after a blank line; a list item's code is indented 6) whose
// first line is a planet command and which have at least one line of output under it.
std::vector<Example> readmeExamples(const std::string& readme) {
  const std::vector<std::string> lines = splitLines(readme);
  std::vector<Example> examples;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (isBlank(lines[i]) || indentOf(lines[i]) < 4 || (i > 0 && !isBlank(lines[i - 1]))) continue;
    const size_t indent = indentOf(lines[i]);
    size_t end = i + 1;
    while (end < lines.size() && !isBlank(lines[end]) && indentOf(lines[end]) >= indent) ++end;
    Example example{int(i + 1), lines[i].substr(indent), {}};
    for (size_t k = i + 1; k < end; ++k) example.output.push_back(lines[k].substr(indent));
    if (std::regex_match(example.command, kCommand) && !example.output.empty()) examples.push_back(example);
    i = end - 1;
  }
  return examples;
}

// A line with a timing or a throughput in it, whose figures change from run to run.
bool reportsTiming(const std::string& line) {
  static const std::regex timing(R"([0-9] s\b|thousand a second|\bthreads?\b)");
  return std::regex_search(line, timing);
}

// The line as compared: numbers become '#' in timing lines ("1 thread" reads as "# threads").
std::string comparable(const std::string& line) {
  if (!reportsTiming(line)) return line;
  static const std::regex number(R"([-+]?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?)");
  static const std::regex oneThread(R"(# thread\b)");
  return std::regex_replace(std::regex_replace(line, number, "#"), oneThread, "# threads");
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Runs the example's command with PLANET_EXE in place of `planet`, in `dir` (where the files it
// names are written), and returns its standard output followed by its standard error.
std::string runExample(const Example& example, const std::filesystem::path& dir, int& exitCode) {
  std::smatch match;
  std::regex_match(example.command, match, kCommand);
  const std::string command = match[1].str() + quoted(PLANET_EXE) + match[2].str();
  const std::string out = (dir / ".stdout").string(), err = (dir / ".stderr").string();
  const std::string shell = "cd " + quoted(dir.string()) + " && " + command + " > " + quoted(out) + " 2> " + quoted(err);
  const int status = std::system(shell.c_str());
  exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // Work that outlasts 10 s logs a progress line to a non-terminal stderr (cli_common's
  // ProgressLine): a sanitizer build's export does; the README shows what a user's run prints.
  static const std::regex kProgress(R"(.* \[[#.]+\] +[0-9]+ %.*)");
  std::string errText;
  for (const std::string& line : splitLines(readFileBytes(err)))
    if (!std::regex_match(line, kProgress)) errText += line + "\n";
  return readFileBytes(out) + errText;
}

std::vector<Example> examplesOfTheReadme() {
  const std::string readme = readFileBytes(std::string(PLANET_SOURCE_DIR) + "/README.md");
  EXPECT_FALSE(readme.empty()) << "cannot read " << PLANET_SOURCE_DIR << "/README.md";
  return readmeExamples(readme);
}

// The parser itself: a block needs the blank line before it, the command first and output after.
TEST(ReadmeExamples, BlocksWithACommandAndItsOutputAreFound) {
  const std::string text =
      "Text\n\n    planet noise --type fbm\n    0.5\n\n"  // found
      "- item:\n\n      printf '1 2 3\\n' | planet noise\n      0.25\n      -1\n\n"  // found, in a list
      "    planet render --out a.png\n\n"  // no output: not run
      "    ls -l\n    total 0\n\n"  // not planet
      "text\n    planet noise\n    1\n";  // no blank line before: a paragraph's continuation
  const std::vector<Example> examples = readmeExamples(text);
  ASSERT_EQ(examples.size(), 2u);
  EXPECT_EQ(examples[0].line, 3);
  EXPECT_EQ(examples[0].command, "planet noise --type fbm");
  EXPECT_EQ(examples[0].output, std::vector<std::string>{"0.5"});
  EXPECT_EQ(examples[1].line, 8);
  EXPECT_EQ(examples[1].command, "printf '1 2 3\\n' | planet noise");
  EXPECT_EQ(examples[1].output, (std::vector<std::string>{"0.25", "-1"}));

  EXPECT_EQ(comparable("wrote a.png (heights -1.5 .. 2 m)"), "wrote a.png (heights -1.5 .. 2 m)");
  EXPECT_EQ(comparable("1024 heights in 1.32 s on 2 threads (396 thousand a second)"),
            "# heights in # s on # threads (# thousand a second)");
  EXPECT_EQ(comparable("in 0.5 s on 1 thread"), comparable("in 0.39 s on 2 threads"));
}

TEST(ReadmeExamples, EveryExampleWithOutputPrintsWhatTheReadmeShows) {
  const std::vector<Example> examples = examplesOfTheReadme();
  // noise, export heightmap and export mesh today: fewer means the parser lost some.
  EXPECT_GE(examples.size(), 3u);
  for (const Example& example : examples) {
    SCOPED_TRACE("README.md:" + std::to_string(example.line) + ": " + example.command);
    const TempDir dir("readme_example");
    int exitCode = -1;
    const std::vector<std::string> printed = splitLines(runExample(example, dir.path(), exitCode));
    EXPECT_EQ(exitCode, 0);
    std::vector<std::string> expected, actual;
    for (const std::string& line : example.output) expected.push_back(comparable(line));
    for (const std::string& line : printed) actual.push_back(comparable(line));
    std::string shown;  // as it would be pasted into the README
    for (const std::string& line : printed) shown += "    " + line + "\n";
    EXPECT_EQ(actual, expected) << "printed:\n" << shown;
  }
}

}  // namespace
}  // namespace planet::test
