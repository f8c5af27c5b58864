#include "graph/gltf/uri.h"

#include <doctest/doctest.h>

using namespace lamina::gltf;

TEST_CASE("uri_encode keeps RFC 3986's unreserved characters and percent-encodes every other byte") {
  CHECK(uri_encode("car_paint-2.v1~.bin") == "car_paint-2.v1~.bin");
  CHECK(uri_encode("my scene#1%.bin") == "my%20scene%231%25.bin");
  // '+' too: some readers decode a literal '+' as a space (form encoding).
  CHECK(uri_encode("a+b.bin") == "a%2Bb.bin");
  // UTF-8 bytes one by one (U+00FC, u with diaeresis, is C3 BC).
  CHECK(uri_encode("m\xc3\xbcller.bin") == "m%C3%BCller.bin");
  CHECK(uri_encode("?/:") == "%3F%2F%3A");
}

TEST_CASE("uri_decode undoes uri_encode, keeps '+' and any '%' that is not followed by two hex digits") {
  for (const char* name : {"my scene#1%.bin", "a+b c.png", "m\xc3\xbcller.bin", "100%", "%zz"})
    CHECK(uri_decode(uri_encode(name)) == name);
  CHECK(uri_decode("a+b%20c%2b") == "a+b c+");
  CHECK(uri_decode("50%") == "50%");
  CHECK(uri_decode("%4") == "%4");
  CHECK(uri_decode("%G1x") == "%G1x");
}
