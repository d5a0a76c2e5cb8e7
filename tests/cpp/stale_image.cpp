// The C++ loader never runs a stale image (docs/compat.md, "Never stale"): the drop-in SCT given
// "x/supervisor.yaml" reads x/supervisor.svm through swarmvm::load_beside, which refuses a missing
// image and one packed from other bytes of the YAML file (a SHA-256 of them, detail::sha256).
// Usage, one line out per argument, checked by tests/cpp/test_stale_image_cpp.py:
//   stale_image open PATH...    "ok STATES" (the exact step's state string before any step, so
//                               where it starts) or "refused: MESSAGE"
//   stale_image sha256 FILE...  the SHA-256 of the file's bytes, in hex
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "swarmvm.hpp"

namespace {

std::string hex(const std::string& bytes) {
    static const char digits[] = "0123456789abcdef";
    std::string out;
    for (unsigned char b : bytes) {
        out += digits[b >> 4];
        out += digits[b & 0xFu];
    }
    return out;
}

std::string open(const std::string& path) {
    try {
        swarmvm::SCT sct(path, swarmvm::Options(), swarmvm::XorShift32(), swarmvm::Step::exact);
        return "ok " + sct.get_current_state_string();
    } catch (const std::runtime_error& error) {
        return std::string("refused: ") + error.what();
    }
}

std::string digest(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return hex(swarmvm::detail::sha256(bytes));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return 2;
    const std::string verb = argv[1];
    for (int i = 2; i < argc; ++i) {
        const std::string line = verb == "open" ? open(argv[i]) : digest(argv[i]);
        std::printf("%s\n", line.c_str());
    }
    return verb == "open" || verb == "sha256" ? 0 : 2;
}
