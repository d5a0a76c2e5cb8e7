// swarmvm table image format (docs/image-format.md), for the C++ runtime (swarmvm_vm.hpp includes it).
// Generated from runtime_py/swarmvm_format.py by scripts/format_headers.py: do not edit.
// After a change of the format run `make format-headers`: tests/compiler/test_format_headers.py
// fails while this copy differs from what the script writes.
#ifndef SWARMVM_FORMAT_HPP
#define SWARMVM_FORMAT_HPP

#include <cstddef>
#include <cstdint>

namespace swarmvm {

constexpr std::uint8_t kFormatVersion = 1;
constexpr std::uint32_t kMagic = 0x494D5653u;       // "SVMI", as a little-endian u32
constexpr std::size_t kHeaderSize = 16;
constexpr std::size_t kCrcSize = 2;
constexpr std::size_t kMinImageSize = 18;           // header and checksum
constexpr std::size_t kMaxImageSize = 65535;        // the length field is a u16
constexpr std::size_t kAtMagic = 0;                 // offset of the header's magic
constexpr std::size_t kAtVersion = 4;               // offset of the header's version
constexpr std::size_t kAtFlags = 5;                 // offset of the header's flags
constexpr std::size_t kAtNumEvents = 6;             // offset of the header's num_events
constexpr std::size_t kAtNumSupervisors = 7;        // offset of the header's num_supervisors
constexpr std::size_t kAtNumStates = 8;             // offset of the header's num_states
constexpr std::size_t kAtNumTransitions = 10;       // offset of the header's num_transitions
constexpr std::size_t kAtStateWidth = 12;           // offset of the header's state_width
constexpr std::size_t kAtMaskBytes = 13;            // offset of the header's mask_bytes
constexpr std::size_t kAtLength = 14;               // offset of the header's length
constexpr std::uint8_t kFlagNames = 1;              // the names section is present
constexpr std::uint8_t kFlagProbs = 2;              // the probability section is present
constexpr std::uint8_t kFlagOrder = 4;              // the order section (source-file event indices) is present
constexpr std::uint8_t kFlagSource = 8;             // the source section (the compatibility layers': skipped) is present
constexpr std::uint8_t kKnownFlags = 15;            // an image with any other flag bit is refused
constexpr unsigned kMaxEvents = 255;                // the format's limits: a build's SVM_MAX_* stay within them
constexpr unsigned kMaxSupervisors = 255;
constexpr unsigned kMaxStates = 65535;
constexpr std::uint32_t kQ15One = 32768;            // probability 1 in the probability section's Q15
constexpr std::uint16_t kCrc16Init = 65535;         // the checksum's start (CRC-16/MCRF4XX)
constexpr std::size_t kStreamChunkData = 8;         // image bytes in a stream chunk

// Why a reader refuses an image: the numbers of swarmvm.h's SVM_ERR_* (swarmvm_format.ErrorCode),
// so every runtime gives the same code for the same bad image.
enum class ErrorCode : int {
    length = 1,   // shorter than MIN_IMAGE_SIZE, longer than MAX_IMAGE_SIZE, or L != the length
    magic = 2,    // not MAGIC
    version = 3,  // a format version this reader does not read
    crc = 4,      // checksum mismatch
    layout = 5    // header inconsistent, sections do not end at L-2, an index or name out of range, or else what the compiler never writes (a name given twice, ...: docs/image-format.md)
};

}  // namespace swarmvm

#endif
