// RTDE's TCP on loopback: a client and a controller session over real sockets, the connection's
// end seen by the reader, an address nobody listens on, and a peer that stops reading.
#include <gtest/gtest.h>

#include "rtde/client_session.hpp"
#include "rtde/server_session.hpp"
#include "rtde/tcp.hpp"

namespace wysiwyf::robot::rtde {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Reads what has arrived on `s` into `framer`; hands each package to `take`.
template <typename Take>
bool drain(TcpStream& s, PackageFramer& framer, Take take) {
  Bytes in;
  const bool ok = s.receive(in);
  framer.feed(in.data(), in.size());
  while (const auto pkg = framer.next()) take(*pkg);
  return ok;
}

TEST(RtdeTcp, AClientAndAControllerSessionStreamOverLoopback) {
  TcpListener listener("127.0.0.1", 0);
  TcpStream client_end = TcpStream::connect("127.0.0.1", listener.port(), 1.0);
  TcpStream server_end = listener.accept(1.0);
  ASSERT_TRUE(server_end.open());
  InputOwners owners;
  ServerSession server({5, 11, 3, 0}, owners);
  ClientSession client(500, {{"timestamp", FieldType::kDouble}}, {{"input_int_register_24", FieldType::kInt32}});
  PackageFramer at_server, at_client;
  Bytes out;
  client.begin(out);
  ASSERT_TRUE(client_end.send(out));
  for (int i = 0; i < 200 && !client.streaming() && !client.failed(); ++i) {
    server_end.wait_readable(0.05);
    Bytes replies;
    ASSERT_TRUE(drain(server_end, at_server, [&](const RawPackage& p) { server.handle(p, replies); }));
    ASSERT_TRUE(server_end.send(replies));
    client_end.wait_readable(0.05);
    Bytes next;
    ASSERT_TRUE(drain(client_end, at_client, [&](const RawPackage& p) { client.handle(p, next); }));
    ASSERT_TRUE(client_end.send(next));
  }
  ASSERT_TRUE(client.streaming()) << client.error();
  server.outputs()->set_double(0, 3.5);
  Bytes data;
  server.encode_outputs(data);
  ASSERT_TRUE(server_end.send(data));
  int taken = 0;
  for (int i = 0; i < 100 && taken == 0; ++i) {
    client_end.wait_readable(0.05);
    Bytes ignored;
    drain(client_end, at_client, [&](const RawPackage& p) { taken += client.handle(p, ignored) ? 1 : 0; });
  }
  EXPECT_EQ(taken, 1);
  EXPECT_EQ(client.outputs().get_double(0), 3.5);

  server_end.close();  // the controller goes away: the client's next read says so
  Bytes in;
  for (int i = 0; i < 100 && client_end.open(); ++i) {
    client_end.wait_readable(0.05);
    client_end.receive(in);
  }
  EXPECT_FALSE(client_end.open());
  EXPECT_EQ(client_end.error(), "the peer closed the connection");
}

TEST(RtdeTcp, ConnectingWhereNobodyListensSaysWhere) {
  std::uint16_t port;
  {
    TcpListener listener("127.0.0.1", 0);
    port = listener.port();
  }  // closed again: nobody listens there now
  try {
    TcpStream::connect("127.0.0.1", port, 0.5);
    ADD_FAILURE() << "connected to a closed port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(port)), std::string::npos) << e.what();
  }
  EXPECT_THROW(TcpStream::connect("no-such-host.invalid", 30004, 0.5), std::runtime_error);
  EXPECT_THROW(TcpListener("not an address", 0), std::runtime_error);
}

TEST(RtdeTcp, APeerThatStopsReadingIsDroppedNotBufferedWithoutBound) {
  TcpListener listener("127.0.0.1", 0);
  TcpStream writer = TcpStream::connect("127.0.0.1", listener.port(), 1.0);
  TcpStream reader = listener.accept(1.0);  // never reads
  ASSERT_TRUE(reader.open());
  const Bytes chunk(64 * 1024, 0x55);
  bool sent = true;
  for (int i = 0; i < 1000 && sent; ++i) sent = writer.send(chunk, 256 * 1024);
  EXPECT_FALSE(sent);
  EXPECT_FALSE(writer.open());
  EXPECT_NE(writer.error().find("the peer stopped reading"), std::string::npos) << writer.error();
}

}  // namespace
}  // namespace wysiwyf::robot::rtde
