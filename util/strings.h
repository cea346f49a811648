// Small string helpers shared by the configuration and command-line code.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace attend {

// Levenshtein distance between two strings.
int EditDistance(std::string_view a, std::string_view b);

// The candidate closest to `word` by edit distance, or "" when none is close enough to be a
// plausible typo (distance above max(2, |word| / 2)).
std::string ClosestMatch(std::string_view word, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" or "" when there is no close candidate.
std::string DidYouMean(std::string_view word, const std::vector<std::string>& candidates);

// Splits on a separator; empty fields are kept.
std::vector<std::string> Split(std::string_view text, char separator);

// The byte offset of the first byte of `text` that is not part of valid UTF-8 (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF), or npos when all of it is valid.
size_t InvalidUtf8At(std::string_view text);

// The byte offset of the first character of valid UTF-8 `text` that YAML does not allow in a
// stream (YAML 1.2, 5.1: the C0 controls but tab, line feed and carriage return; DEL; the C1
// controls but NEL, U+0085), or npos when there is none. A NUL in a key, for one, is read by
// yaml-cpp but not written back as the same bytes.
size_t NonPrintableAt(std::string_view text);

// The shortest text that reads back as exactly `value` (std::to_chars).
std::string ShortestNumber(double value);

// The same for a float: the shortest text that reads back as `value` as a float ("0.2").
std::string ShortestFloat(float value);

// `text` with ASCII letters in lower case (file extensions, case-blind names).
std::string Lowercase(std::string text);

// `value` with `digits` decimals ("%.*f").
std::string Fixed(double value, int digits);

// `text` as it may be shown in a message: whole when at most `max` bytes, else its first
// `max` bytes (cut at a UTF-8 character boundary) and "... (N bytes)". A value of 100 MB in a
// configuration is named, not echoed.
std::string Abbreviate(std::string_view text, size_t max = 120);

// Joins with a separator.
std::string Join(const std::vector<std::string>& parts, std::string_view separator);

// The 64-bit FNV-1a hash of `text`: a stable fingerprint for names and cache folders.
std::uint64_t Fnv1a(std::string_view text);

}  // namespace attend
