// The session store on a real PostgreSQL server, which this test starts on a Unix socket of its
// own (Debian's postgresql: initdb and pg_ctl under /usr/lib/postgresql/N/bin; as root the server
// runs as the postgres user). The schema is migrated once and kept; two workstations write at
// once and lose nothing; a server that goes away mid-session leaves the sessions in the local
// spool, and they reach it when it is back. Skips, saying why, where the server is not installed.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "dentsph/report/session_store.hpp"
#include "report/store_schema.hpp"
#include "report_support.hpp"

namespace dentsph::report {
namespace {

namespace fs = std::filesystem;

fs::path postgres_bin() {
  if (!fs::exists("/usr/lib/postgresql")) return {};
  for (const auto& d : fs::directory_iterator("/usr/lib/postgresql"))
    if (fs::exists(d.path() / "bin" / "initdb") && fs::exists(d.path() / "bin" / "pg_ctl")) return d.path() / "bin";
  return {};
}

// A throwaway server: initdb into a temporary folder, listening on a socket there only.
class Server {
 public:
  bool start_fresh() {
    bin_ = postgres_bin();
    if (bin_.empty()) return false;
    dir_ = fs::temp_directory_path() / ("dentsph_pg_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    port_ = 20000 + int(::getpid() % 20000);
    as_ = ::geteuid() == 0 ? "runuser -u postgres -- " : "";
    if (::geteuid() == 0 && std::system(("chown postgres " + dir_.string()).c_str()) != 0) return false;
    const std::string init = as_ + (bin_ / "initdb").string() + " -D " + (dir_ / "data").string() +
                             " -U postgres --auth=trust -E UTF8 > " + (dir_ / "initdb.log").string() + " 2>&1";
    if (std::system(init.c_str()) != 0) return false;
    return start();
  }
  bool start() {
    const std::string cmd = as_ + (bin_ / "pg_ctl").string() + " -D " + (dir_ / "data").string() + " -l " +
                            (dir_ / "server.log").string() + " -w -t 60 -o \"-c listen_addresses='' -c unix_socket_directories='" +
                            dir_.string() + "' -p " + std::to_string(port_) + "\" start > /dev/null 2>&1";
    return std::system(cmd.c_str()) == 0;
  }
  // Gone at once, as when its machine loses power: no goodbye to the clients.
  void kill() {
    const std::string cmd = as_ + (bin_ / "pg_ctl").string() + " -D " + (dir_ / "data").string() +
                            " -m immediate -w stop > /dev/null 2>&1";
    (void)std::system(cmd.c_str());
  }
  ~Server() {
    if (!dir_.empty()) {
      kill();
      fs::remove_all(dir_);
    }
  }
  std::string location() const {
    return "postgresql:///postgres?host=" + dir_.string() + "&port=" + std::to_string(port_) + "&user=postgres";
  }
  fs::path spool() const { return dir_ / "spool"; }
  std::string log() const {
    std::ifstream in(dir_ / "server.log");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }

 private:
  fs::path bin_, dir_;
  int port_ = 0;
  std::string as_;
};

Server& server() {
  static Server s;
  return s;
}

class PostgresStore : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { started_ = server().start_fresh(); }
  void SetUp() override {
    if (postgres_bin().empty()) GTEST_SKIP() << "PostgreSQL is not installed (Debian's postgresql; install-deps.sh installs it)";
    if (!started_) GTEST_SKIP() << "the test's PostgreSQL server did not start: " << server().log();
  }
  static SessionEntry entry(const std::string& student, const std::string& when) {
    nlohmann::json s = testing::summary(0.97, 0, 1.0, 2.0, 1.0);
    SessionEntry e;
    e.student = student;
    e.exercise = "class I";
    e.finished_at = when;
    e.summary = s;
    e.procedure = {{"increments", {{{"index", 1}, {"thickness_p90_mm", 0.875}}}}};
    return e;
  }
  static inline bool started_ = false;
};

TEST_F(PostgresStore, MigratesOnceAndKeepsSessions) {
  {
    SessionStore store(server().location(), server().spool());
    EXPECT_EQ(store.schema_version(), current_store_version());
    EXPECT_GT(store.add(entry("pg one", "2026-01-02T10:00:00Z")), 0);
    EXPECT_GT(store.add(entry("pg one", "2026-01-01T10:00:00Z")), 0);
  }
  const SessionStore again(server().location(), server().spool());
  EXPECT_EQ(again.schema_version(), current_store_version());
  const auto found = again.find("pg one", "class I");
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].finished_at, "2026-01-01T10:00:00Z");  // oldest first
  EXPECT_EQ(found[0].summary, testing::summary(0.97, 0, 1.0, 2.0, 1.0));
  EXPECT_EQ(found[0].procedure["increments"][0]["thickness_p90_mm"], 0.875);
  EXPECT_EQ(again.pending(), 0u);
}

TEST_F(PostgresStore, TwoWorkstationsWritingAtOnceLoseNothing) {
  auto workstation = [](const std::string& student) {
    SessionStore s(server().location(), server().spool());  // each its own connection
    for (int k = 0; k < 25; ++k) s.add(entry(student, "2026-02-01T10:00:" + std::to_string(10 + k) + "Z"));
  };
  std::thread a(workstation, "pg first"), b(workstation, "pg second");
  a.join();
  b.join();
  const SessionStore s(server().location(), server().spool());
  EXPECT_EQ(s.find("pg first", "").size(), 25u);
  EXPECT_EQ(s.find("pg second", "").size(), 25u);
}

TEST_F(PostgresStore, AServerThatGoesAwayGetsTheSessionsLater) {
  SessionStore store(server().location(), server().spool());
  ASSERT_GT(store.add(entry("pg away", "2026-03-01T10:00:00Z")), 0);
  server().kill();  // the connection the store holds is now dead: the next write is lost mid-way
  EXPECT_EQ(store.add(entry("pg away", "2026-03-02T10:00:00Z")), 0);
  EXPECT_EQ(store.add(entry("pg away", "2026-03-03T10:00:00Z")), 0);
  EXPECT_EQ(store.pending(), 2u);
  try {
    store.find("pg away", "");
    ADD_FAILURE() << "found sessions on a server that is down";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be reached"), std::string::npos) << e.what();
  }
  // Opening another store while the server is still down keeps them too.
  { SessionStore offline(server().location(), server().spool()); EXPECT_EQ(offline.pending(), 2u); }
  ASSERT_TRUE(server().start()) << server().log();
  const SessionStore back(server().location(), server().spool());  // reaching it sends the spool
  EXPECT_EQ(back.pending(), 0u);
  const auto found = back.find("pg away", "");
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[1].finished_at, "2026-03-02T10:00:00Z");
  EXPECT_EQ(found[2].finished_at, "2026-03-03T10:00:00Z");
}

TEST(PostgresAddress, PasswordsAreMaskedInMessages) {
  EXPECT_EQ(masked_location("postgresql://tutor:s3cret@db.school/dentsph"), "postgresql://tutor:***@db.school/dentsph");
  EXPECT_EQ(masked_location("postgresql://tutor@db.school/dentsph"), "postgresql://tutor@db.school/dentsph");
  EXPECT_EQ(masked_location("sessions.sqlite"), "sessions.sqlite");
  EXPECT_TRUE(is_postgres_location("postgres://x/y"));
  EXPECT_FALSE(is_postgres_location("postgresql.sqlite"));
  // libpq's key-value form (an SQLite file of that name was made, the password printed in clear).
  EXPECT_TRUE(is_postgres_location("host=127.0.0.1 port=1 password=s3cret dbname=x"));
  EXPECT_TRUE(is_postgres_location("  dbname = dentsph"));
  EXPECT_FALSE(is_postgres_location("sessions=2026.sqlite"));
  EXPECT_FALSE(is_postgres_location("runs/host=a.sqlite"));
  EXPECT_EQ(masked_location("host=127.0.0.1 port=1 password=s3cret dbname=x"), "host=127.0.0.1 port=1 password=*** dbname=x");
  EXPECT_EQ(masked_location("host=db password = 'two words\\' here' user=tutor"), "host=db password = *** user=tutor");
  EXPECT_EQ(masked_location("postgresql://db/dentsph?user=tutor&password=s3cret&sslmode=require"),
            "postgresql://db/dentsph?user=tutor&password=***&sslmode=require");
  EXPECT_EQ(masked_location("host=db user=passwordless"), "host=db user=passwordless");
}

}  // namespace
}  // namespace dentsph::report
