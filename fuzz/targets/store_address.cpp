// Fuzz target: a session store's address (`--db`), as the command line hands it: which backend it
// names (is_postgres_location) and how it is shown in messages (masked_location). No crash, and
// the mask is idempotent (a masked address masks to itself, so a message never shows a password
// that a second pass would have hidden), and every password=... parameter that begins a key
// (after a space, a tab, '?' or '&'), quoted or not, shows *** as its value.
#include <cstdlib>
#include <string>

#include "dentsph/report/session_store.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

int store_address(const std::uint8_t* data, std::size_t size) {
  const std::string address(reinterpret_cast<const char*>(data), size);
  (void)report::is_postgres_location(address);
  const std::string masked = report::masked_location(address);
  if (report::masked_location(masked) != masked) std::abort();
  // Every password= that begins a key (after a space, a tab, '?' or '&') shows *** as its value.
  for (std::size_t p = masked.find("password"); p != std::string::npos; p = masked.find("password", p + 1)) {
    if (p > 0 && masked[p - 1] != ' ' && masked[p - 1] != '\t' && masked[p - 1] != '?' && masked[p - 1] != '&')
      continue;
    std::size_t v = p + 8;
    while (v < masked.size() && masked[v] == ' ') ++v;
    if (v >= masked.size() || masked[v] != '=') continue;
    ++v;
    while (v < masked.size() && masked[v] == ' ') ++v;
    if (masked.compare(v, 3, "***") != 0) std::abort();
  }
  return 0;
}

}  // namespace dentsph::fuzz
