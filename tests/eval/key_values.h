// What the judge's scripts print: "key=value" lines; and a scratch folder per test.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace slim::test {

// The numeric values of "key=value" lines (lines whose value does not start with a number, such
// as "slicer=prusa", are left out; "0,0,1" reads as its first number).
std::map<std::string, double> parse_key_values(const std::string& text);
std::map<std::string, double> read_key_values(const std::filesystem::path& file);

// root/name, emptied and created. Kept after the test (the next run overwrites it): the reports
// and G-codes in it are worth a look.
std::filesystem::path scratch_dir(const std::filesystem::path& root, const std::string& name);

}  // namespace slim::test
