#include <utility>  // before Asio: Boost 1.74 needs it
// The management endpoint: framing, and a real loopback server and client.
#include <gtest/gtest.h>

#include <thread>

#include "server/management/management_client.hpp"
#include "server/management/management_server.hpp"

namespace netmc::management {
namespace {

netmc::v1::Request submit_request(std::uint64_t id) {
  netmc::v1::Request request;
  request.set_request_id(id);
  request.mutable_submit()->mutable_spec()->set_plant("seed001");
  return request;
}

TEST(FrameCodec, RoundTripWithSplitAndJoinedFrames) {
  const std::string bytes = encode_frame(submit_request(7)) + encode_frame(submit_request(8));
  ASSERT_EQ(static_cast<unsigned char>(bytes[3]), submit_request(7).ByteSizeLong());  // big-endian length
  FrameDecoder decoder;
  std::vector<std::uint64_t> ids;
  for (char byte : bytes) {  // one byte at a time: every split point
    decoder.feed(&byte, 1);
    while (auto payload = decoder.next()) {
      netmc::v1::Request request;
      ASSERT_TRUE(request.ParseFromString(*payload));
      ids.push_back(request.request_id());
    }
  }
  EXPECT_EQ(ids, (std::vector<std::uint64_t>{7, 8}));
}

TEST(FrameCodec, RejectsOversizeFrames) {
  FrameDecoder decoder;
  const char header[4] = {0x7f, 0x00, 0x00, 0x00};
  decoder.feed(header, 4);
  EXPECT_THROW(decoder.next(), FrameError);
}

TEST(ManagementEndpoint, StreamsResponsesInOrderFromAnotherThread) {
  boost::asio::io_context io;
  std::vector<std::thread> workers;
  ManagementServer server(io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request& request) {
    netmc::v1::Response accepted;
    accepted.set_request_id(request.request_id());
    accepted.mutable_accepted()->set_job_id(42);
    session.send(accepted);
    workers.emplace_back([self = session.shared_from_this(), id = request.request_id()] {
      for (std::uint32_t i = 1; i <= 5; ++i) {
        netmc::v1::Response update;
        update.set_request_id(id);
        update.mutable_iteration()->mutable_metrics()->set_iteration(i);
        self->send(update);
      }
      netmc::v1::Response finished;
      finished.set_request_id(id);
      finished.mutable_finished()->set_state("done");
      self->send(finished);
    });
  }});
  std::thread io_thread([&] { io.run(); });

  ManagementClient client("127.0.0.1:" + std::to_string(server.port()), std::chrono::seconds(2));
  client.send(submit_request(3));
  auto response = client.receive(std::chrono::seconds(2));
  ASSERT_TRUE(response && response->has_accepted());
  EXPECT_EQ(response->accepted().job_id(), 42u);
  for (std::uint32_t i = 1; i <= 5; ++i) {
    response = client.receive(std::chrono::seconds(2));
    ASSERT_TRUE(response && response->has_iteration());
    EXPECT_EQ(response->iteration().metrics().iteration(), i);
    EXPECT_EQ(response->request_id(), 3u);
  }
  response = client.receive(std::chrono::seconds(2));
  ASSERT_TRUE(response && response->has_finished());
  EXPECT_FALSE(client.receive(std::chrono::milliseconds(50)).has_value());  // timeout, no hang

  server.stop();
  io.stop();
  io_thread.join();
  for (auto& worker : workers) worker.join();
}

TEST(ManagementEndpoint, MalformedFrameGetsAnErrorAndTheConnectionCloses) {
  boost::asio::io_context io;
  ManagementServer server(io, "127.0.0.1", 0, {[](Session&, const netmc::v1::Request&) {}});
  std::thread io_thread([&] { io.run(); });
  boost::asio::io_context client_io;
  boost::asio::ip::tcp::socket socket(client_io);
  socket.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  const char garbage[] = {0x00, 0x00, 0x00, 0x03, '\xff', '\xff', '\xff'};
  boost::asio::write(socket, boost::asio::buffer(garbage, sizeof garbage));
  std::string received;
  boost::system::error_code error;
  std::array<char, 256> buffer{};
  while (!error) {
    const std::size_t n = socket.read_some(boost::asio::buffer(buffer), error);
    received.append(buffer.data(), n);
  }
  FrameDecoder decoder;
  decoder.feed(received.data(), received.size());
  const auto payload = decoder.next();
  ASSERT_TRUE(payload.has_value());
  netmc::v1::Response response;
  ASSERT_TRUE(response.ParseFromString(*payload));
  EXPECT_NE(response.error().message().find("not a netmc.v1.Request"), std::string::npos);
  server.stop();
  io.stop();
  io_thread.join();
}

TEST(ManagementClient, ClearErrors) {
  EXPECT_THROW(ManagementClient("localhost", std::chrono::seconds(1)), std::invalid_argument);
  EXPECT_THROW(ManagementClient("localhost:http", std::chrono::seconds(1)), std::invalid_argument);
  // A port nobody listens on: take a free one, then close it.
  boost::asio::io_context io;
  boost::asio::ip::tcp::acceptor probe(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
  const auto port = probe.local_endpoint().port();
  probe.close();
  try {
    ManagementClient client("127.0.0.1:" + std::to_string(port), std::chrono::seconds(1));
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:" + std::to_string(port)), std::string::npos);
  }
}

}  // namespace
}  // namespace netmc::management
