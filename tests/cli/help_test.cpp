// `iblab --help` and each sub-command's read like a finished tool's: a numeric option shows
// its type (FLOAT, INT), not CLI11's TEXT, and a default is printed short (0.3, not a float's
// double expansion 0.30000001192092896).
#include <cctype>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.hpp"

namespace iblab::cli_testing {
namespace {

// Significant digits of a number as written ("0.30000001192092896" -> 17, "45" -> 2,
// "1e-06" -> 1, "1024" -> 4): the mantissa's digits without leading zeros; trailing zeros
// of a whole number count, since "1024" has four.
int significantDigits(const std::string& number)
{
    std::string mantissa = number.substr(0, number.find_first_of("eE"));
    if (!mantissa.empty() && (mantissa[0] == '-' || mantissa[0] == '+')) mantissa.erase(0, 1);
    std::string digits;
    for (char c : mantissa)
        if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
    const std::size_t first = digits.find_first_not_of('0');
    return first == std::string::npos ? 1 : int(digits.size() - first);
}

bool isNumber(const std::string& text) { return std::regex_match(text, std::regex(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)")); }

// The problems of one help text: every option line ("  --name TYPE=DEFAULT  help", the help
// possibly on the next line) whose type is TEXT while its default is a number or its help
// gives a numeric range ("[0..1]", "[>= 1]"), and every default with a number of more than 6
// significant digits (colours "r,g,b" are checked per component).
std::vector<std::string> helpProblems(const std::string& help)
{
    std::vector<std::string> problems;
    std::istringstream lines(help);
    std::string line;
    const std::regex option(R"(^\s+(-[^\s]+)(?:\s+([^\s=]+)(?:=(\S+))?)?(.*)$)");
    const std::regex numericRange(R"(\[(>= |<= )?[-+]?[\d.]+(e[-+]?\d+)?(\.\.[-+]?[\d.]+(e[-+]?\d+)?)?\])");
    std::vector<std::string> all;
    while (std::getline(lines, line)) all.push_back(line);
    for (std::size_t i = 0; i < all.size(); ++i) {
        std::smatch m;
        if (!std::regex_match(all[i], m, option)) continue;
        const std::string name = m[1], type = m[2], defaultText = m[3];
        // The help follows on the line itself or, after a long name, on the next one.
        std::string text = m[4];
        if (i + 1 < all.size() && !all[i + 1].empty() && all[i + 1].find_first_not_of(' ') > 20) text += " " + all[i + 1];
        const bool numericDefault = !defaultText.empty() && isNumber(defaultText);
        if (type == "TEXT" && (numericDefault || std::regex_search(text, numericRange)))
            problems.push_back(name + ": TEXT beside a numeric option: " + all[i]);
        std::istringstream parts(defaultText);
        std::string part;
        while (std::getline(parts, part, ','))
            if (isNumber(part) && significantDigits(part) > 6) problems.push_back(name + ": default with more than 6 significant digits: " + all[i]);
    }
    return problems;
}

std::string joined(const std::vector<std::string>& problems)
{
    std::string out;
    for (const std::string& p : problems) out += p + "\n";
    return out;
}

// The checker itself finds what it is for: lines as CLI11 printed them before numeric options
// had their types (and one correct line, which it leaves alone).
TEST(HelpCheck, FindsTextTypesAndLongDefaults)
{
    const std::string before = "Options:\n"
                               "  --roughness TEXT=0.30000001192092896 [0..1]\n"
                               "                              Perceptual roughness, 0..1\n"
                               "  --fov TEXT=45.0 [1..170]    Vertical field of view, degrees\n"
                               "  --base-color TEXT           Base colour\n"
                               "  --samples TEXT [1..1024]    N, samples per pixel\n"
                               "  --width INT=640             Image width\n";
    const std::vector<std::string> problems = helpProblems(before);
    ASSERT_EQ(problems.size(), 4u) << joined(problems);
    EXPECT_NE(problems[0].find("--roughness: TEXT"), std::string::npos) << problems[0];
    EXPECT_NE(problems[1].find("--roughness: default"), std::string::npos) << problems[1];
    EXPECT_NE(problems[2].find("--fov: TEXT"), std::string::npos) << problems[2];
    EXPECT_NE(problems[3].find("--samples: TEXT"), std::string::npos) << problems[3];
    EXPECT_EQ(significantDigits("0.30000001192092896"), 17);
    EXPECT_EQ(significantDigits("1e-06"), 1);
    EXPECT_EQ(significantDigits("1024"), 4);
}

// Every sub-command that `iblab --help` lists, and the top level itself.
TEST_F(Cli, HelpShowsTypesAndShortDefaults)
{
    const Result top = run("--help");
    ASSERT_EQ(top.exitCode, 0) << top.err;
    EXPECT_EQ(joined(helpProblems(top.out)), "");
    EXPECT_NE(top.out.find("--roughness FLOAT=0.3 "), std::string::npos) << top.out;
    EXPECT_NE(top.out.find("--fov FLOAT=45 "), std::string::npos) << top.out;
    EXPECT_NE(top.out.find("--samples INT="), std::string::npos) << top.out;

    const std::size_t listStart = top.out.find("Subcommands:");
    ASSERT_NE(listStart, std::string::npos) << top.out;
    std::istringstream list(top.out.substr(listStart));
    std::string line;
    std::getline(list, line);
    std::vector<std::string> subcommands;
    while (std::getline(list, line) && !line.empty()) {
        std::istringstream words(line);
        std::string name;
        if (words >> name) subcommands.push_back(name);
    }
    EXPECT_GE(subcommands.size(), 8u) << top.out;
    for (const std::string& sub : subcommands) {
        const Result r = run(sub + " --help");
        ASSERT_EQ(r.exitCode, 0) << sub << ": " << r.err;
        EXPECT_EQ(joined(helpProblems(r.out)), "") << "iblab " << sub << " --help";
    }
}

// Both states of every boolean can be asked for, whatever its default: each flag comes with
// its opposite, and a boolean value option with its --no- form.
TEST_F(Cli, BooleanFlagsHaveBothForms)
{
    const Result r = run("render --scene none --env builtin:white --width 8 --height 8 --no-override-model --override-model "
                         "--no-pdf-filtering --pdf-filtering --no-multiscatter --b-no-multiscatter --b-pdf-filtering "
                         "--no-freeze-samples -o a.png");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    const Result help = run("render --help");
    for (const char* pair : {"--multiscatter,--no-multiscatter", "--no-pdf-filtering,--pdf-filtering",
                             "--override-model,--no-override-model", "--b-no-pdf-filtering,--b-pdf-filtering"})
        EXPECT_NE(help.out.find(pair), std::string::npos) << pair << "\n" << help.out;
    const Result bake = run("bake --help");
    EXPECT_NE(bake.out.find("--no-prefilter-mirror-copy"), std::string::npos) << bake.out;
    // The value the last of two opposite flags sets wins, as on any command line.
    const Result settings = run("render --scene none --env builtin:white --width 8 --height 8 --multiscatter --no-multiscatter -o b.png");
    ASSERT_EQ(settings.exitCode, 0) << settings.err;
    std::ifstream sidecar(dir / "b.png.json");
    const std::string json((std::istreambuf_iterator<char>(sidecar)), {});
    EXPECT_NE(json.find("\"multiscatter\": false"), std::string::npos) << json;
}

} // namespace
} // namespace iblab::cli_testing
