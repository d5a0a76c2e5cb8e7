// The C++ side of tests/compiler/test_reader_parity.py: prints 0 when swarmvm::Image::parse accepts
// an image file named on the command line, else its ImageError's code, one line per file. Each
// image sits in a heap buffer of exactly its size, so that a sanitizer build catches any read
// past it. An argument --load=PATH goes through Image::load instead (bounded read of a file).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "swarmvm.hpp"

static int check(const std::string& arg) {
    try {
        if (arg.rfind("--load=", 0) == 0) {
            swarmvm::Image::load(arg.substr(7));
        } else {
            std::ifstream in(arg, std::ios::binary);
            const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            std::unique_ptr<std::uint8_t[]> exact(new std::uint8_t[bytes.size()]);
            std::copy(bytes.begin(), bytes.end(), exact.get());
            swarmvm::Image::parse(exact.get(), bytes.size());
        }
        return 0;
    } catch (const swarmvm::ImageError& ex) {
        return static_cast<int>(ex.code());
    } catch (const swarmvm::FileError&) {
        return -1;      // --load of a path the input layer refuses (a device, a FIFO, a folder)
    }
}

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) std::cout << check(argv[i]) << "\n";
    return 0;
}
