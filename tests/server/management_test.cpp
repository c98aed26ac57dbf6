#include <utility>  // before Asio: Boost 1.74 needs it
// The management endpoint: framing, and a real loopback server and client. Every wait is
// bounded; the whole suite takes well under a second.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <thread>
#include <vector>

#include "server/management/access_token.hpp"
#include "server/management/management_client.hpp"
#include "server/management/management_server.hpp"
#include "tests/support/io_thread.hpp"

namespace netmc::management {
namespace {

using namespace std::chrono_literals;

netmc::v1::Request submit_request(std::uint64_t id) {
  netmc::v1::Request request;
  request.set_request_id(id);
  request.mutable_submit()->mutable_spec()->set_plant("seed001");
  request.mutable_submit()->mutable_spec()->set_name("job-" + std::to_string(id));
  return request;
}

std::vector<std::uint64_t> drain_ids(FrameDecoder& decoder) {
  std::vector<std::uint64_t> ids;
  while (auto payload = decoder.next()) {
    netmc::v1::Request request;
    EXPECT_TRUE(request.ParseFromString(*payload));
    ids.push_back(request.request_id());
  }
  return ids;
}

using test_support::IoThread;

TEST(FrameCodec, LengthIsFourBytesBigEndian) {
  netmc::v1::Request request = submit_request(1);
  request.mutable_submit()->mutable_spec()->set_name(std::string(300, 'x'));  // length > 255
  const std::string frame = encode_frame(request);
  const auto size = request.ByteSizeLong();
  ASSERT_EQ(frame.size(), 4 + size);
  EXPECT_EQ(static_cast<unsigned char>(frame[0]), 0u);
  EXPECT_EQ(static_cast<unsigned char>(frame[1]), 0u);
  EXPECT_EQ(static_cast<unsigned char>(frame[2]), (size >> 8) & 0xFF);
  EXPECT_EQ(static_cast<unsigned char>(frame[3]), size & 0xFF);
}

TEST(FrameCodec, RoundTripOneByteAtATime) {
  const std::string bytes = encode_frame(submit_request(7)) + encode_frame(submit_request(8));
  FrameDecoder decoder;
  std::vector<std::uint64_t> ids;
  for (char byte : bytes) {  // every split point, header included
    decoder.feed(&byte, 1);
    for (auto id : drain_ids(decoder)) ids.push_back(id);
  }
  EXPECT_EQ(ids, (std::vector<std::uint64_t>{7, 8}));
  EXPECT_EQ(decoder.buffered(), 0u);
}

TEST(FrameCodec, SeveralFramesInOneBufferAndPartialTail) {
  std::string bytes;
  for (std::uint64_t id = 1; id <= 5; ++id) bytes += encode_frame(submit_request(id));
  const std::string sixth = encode_frame(submit_request(6));
  bytes += sixth.substr(0, 6);  // header and part of the payload
  FrameDecoder decoder;
  decoder.feed(bytes.data(), bytes.size());
  EXPECT_EQ(drain_ids(decoder), (std::vector<std::uint64_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(decoder.buffered(), 6u);
  decoder.feed(sixth.data() + 6, sixth.size() - 6);
  EXPECT_EQ(drain_ids(decoder), (std::vector<std::uint64_t>{6}));
}

TEST(FrameCodec, ChunksAcrossFrameBoundaries) {
  std::string bytes;
  for (std::uint64_t id = 1; id <= 20; ++id) bytes += encode_frame(submit_request(id));
  FrameDecoder decoder;
  std::vector<std::uint64_t> ids;
  for (std::size_t at = 0; at < bytes.size(); at += 7) {  // 7 is prime to every frame size here
    decoder.feed(bytes.data() + at, std::min<std::size_t>(7, bytes.size() - at));
    for (auto id : drain_ids(decoder)) ids.push_back(id);
  }
  ASSERT_EQ(ids.size(), 20u);
  for (std::uint64_t i = 0; i < 20; ++i) EXPECT_EQ(ids[i], i + 1);
}

TEST(FrameCodec, EmptyMessageIsAZeroLengthFrame) {
  const std::string frame = encode_frame(netmc::v1::Request{});
  EXPECT_EQ(frame, std::string(4, '\0'));
  FrameDecoder decoder;
  decoder.feed(frame.data(), frame.size());
  const auto payload = decoder.next();
  ASSERT_TRUE(payload.has_value());
  EXPECT_TRUE(payload->empty());
}

TEST(FrameCodec, RejectsOversizeFrames) {
  FrameDecoder decoder;
  // 16 MiB + 1: rejected from the header alone, without waiting for the payload.
  const char header[4] = {0x01, 0x00, 0x00, 0x01};
  decoder.feed(header, 4);
  try {
    decoder.next();
    FAIL() << "an oversize length was accepted";
  } catch (const FrameError& error) {
    EXPECT_NE(std::string(error.what()).find("16 MiB"), std::string::npos) << error.what();
  }
  // Exactly 16 MiB is allowed (incomplete here, so no frame yet).
  FrameDecoder at_limit;
  const char limit[4] = {0x01, 0x00, 0x00, 0x00};
  at_limit.feed(limit, 4);
  EXPECT_FALSE(at_limit.next().has_value());
}

TEST(FrameCodec, EncodeRejectsOversizeMessages) {
  netmc::v1::Request request;
  request.mutable_submit()->mutable_spec()->set_name(std::string(kMaxFrameBytes + 1, 'x'));
  EXPECT_THROW(encode_frame(request), FrameError);
}

TEST(ManagementEndpoint, StreamsResponsesInOrderFromAnotherThread) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  std::vector<std::thread> workers;
  std::shared_ptr<Session> seen;
  ManagementServer server(runner.io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request& request) {
    // On the io thread: accept at once, stream the rest from a worker thread.
    EXPECT_TRUE(request.has_submit());
    EXPECT_EQ(request.submit().spec().plant(), "seed001");
    seen = session.shared_from_this();
    netmc::v1::Response accepted;
    accepted.set_request_id(request.request_id());
    accepted.mutable_accepted()->set_job_id(42);
    session.send(accepted);
    workers.emplace_back([self = session.shared_from_this(), id = request.request_id()] {
      for (std::uint32_t i = 1; i <= 50; ++i) {
        netmc::v1::Response update;
        update.set_request_id(id);
        update.mutable_iteration()->set_job_id(42);
        update.mutable_iteration()->set_total_iterations(50);
        update.mutable_iteration()->mutable_metrics()->set_iteration(i);
        self->send(update);
      }
      netmc::v1::Response finished;
      finished.set_request_id(id);
      finished.mutable_finished()->set_job_id(42);
      finished.mutable_finished()->set_state("done");
      self->send(finished);
    });
  }});
  runner.start();
  ASSERT_NE(server.port(), 0);

  ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
  client.send(submit_request(3));
  auto response = client.receive(2s);
  ASSERT_TRUE(response && response->has_accepted());
  EXPECT_EQ(response->request_id(), 3u);
  EXPECT_EQ(response->accepted().job_id(), 42u);
  for (std::uint32_t i = 1; i <= 50; ++i) {
    response = client.receive(2s);
    ASSERT_TRUE(response && response->has_iteration());
    EXPECT_EQ(response->iteration().metrics().iteration(), i);
    EXPECT_EQ(response->request_id(), 3u);
  }
  response = client.receive(2s);
  ASSERT_TRUE(response && response->has_finished());
  EXPECT_EQ(response->finished().state(), "done");
  EXPECT_FALSE(client.receive(50ms).has_value());  // timeout, no hang, connection kept

  // After a timeout the connection still works.
  client.send(submit_request(4));
  response = client.receive(2s);
  ASSERT_TRUE(response && response->has_accepted());
  EXPECT_EQ(response->request_id(), 4u);

  for (auto& worker : workers) worker.join();
  ASSERT_TRUE(seen);
  EXPECT_TRUE(seen->open());
  server.stop();
  EXPECT_TRUE(runner.finishes_within(2s)) << "io_context::run() did not return after stop()";
  EXPECT_FALSE(seen->open());
  seen->send(netmc::v1::Response{});  // after close: dropped, no crash
}

TEST(ManagementEndpoint, StopWhileAClientIsConnected) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  std::promise<std::shared_ptr<Session>> connected;
  ManagementServer server(runner.io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request&) {
    connected.set_value(session.shared_from_this());  // keep it, answer nothing
  }});
  runner.start();
  ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
  client.send(submit_request(1));
  auto session_future = connected.get_future();
  ASSERT_EQ(session_future.wait_for(2s), std::future_status::ready);
  const auto session = session_future.get();

  const auto started = std::chrono::steady_clock::now();
  std::thread stopper([&] { server.stop(); });  // from another thread than the io thread
  stopper.join();
  try {
    const auto response = client.receive(2s);
    EXPECT_FALSE(response.has_value());
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:" + std::to_string(server.port())), std::string::npos)
        << error.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - started, 1s);  // the close is seen, not the timeout
  EXPECT_TRUE(runner.finishes_within(2s)) << "io_context::run() did not return after stop()";
  EXPECT_FALSE(session->open());
  session->send(netmc::v1::Response{});  // a job thread answering late: dropped, no crash
  server.stop();                         // idempotent

  // Nobody listens any more.
  EXPECT_THROW(ManagementClient("127.0.0.1:" + std::to_string(server.port()), 1s), std::runtime_error);
}

TEST(ManagementEndpoint, ClientClosingEndsTheSession) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  std::promise<std::shared_ptr<Session>> connected;
  ManagementServer server(runner.io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request&) {
    connected.set_value(session.shared_from_this());
  }});
  runner.start();
  {
    ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
    client.send(submit_request(1));
    ASSERT_EQ(connected.get_future().wait_for(2s), std::future_status::ready);
  }  // the client goes away
  server.stop();
  EXPECT_TRUE(runner.finishes_within(2s));
}

// Connects, writes raw bytes (if any) and reads until the server closes (it must, or this test
// hangs until the ctest timeout); returns what came and how long after the write it closed.
struct Received {
  std::string bytes;
  std::chrono::milliseconds closed_after{0};
};

Received read_until_closed(std::uint16_t port, const std::string& bytes) {
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket socket(io);
  socket.connect({boost::asio::ip::make_address("127.0.0.1"), port});
  const auto started = std::chrono::steady_clock::now();
  if (!bytes.empty()) boost::asio::write(socket, boost::asio::buffer(bytes));
  Received received;
  boost::system::error_code error;
  std::array<char, 256> buffer{};
  while (!error) {
    const std::size_t n = socket.read_some(boost::asio::buffer(buffer), error);
    received.bytes.append(buffer.data(), n);
  }
  EXPECT_EQ(error, boost::asio::error::eof);
  received.closed_after =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - started);
  return received;
}

// Writes raw bytes to the server and returns the frames it answers before it closes.
std::vector<netmc::v1::Response> raw_exchange(std::uint16_t port, const std::string& bytes) {
  const std::string received = read_until_closed(port, bytes).bytes;
  FrameDecoder decoder;
  decoder.feed(received.data(), received.size());
  std::vector<netmc::v1::Response> responses;
  while (auto payload = decoder.next()) {
    responses.emplace_back();
    EXPECT_TRUE(responses.back().ParseFromString(*payload));
  }
  return responses;
}

// A handler that counts the requests and accepts each as job 1.
ManagementServer::Handler accept_counting(std::atomic<int>& requests) {
  return {[&requests](Session& session, const netmc::v1::Request& request) {
    session.mark_authenticated();
    ++requests;
    netmc::v1::Response accepted;
    accepted.set_request_id(request.request_id());
    accepted.mutable_accepted()->set_job_id(1);
    session.send(accepted);
  }};
}

TEST(ManagementEndpoint, MalformedFrameGetsAnErrorAndTheConnectionCloses) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  std::atomic<int> requests{0};
  ManagementServer server(runner.io, "127.0.0.1", 0, accept_counting(requests));
  runner.start();
  // A good request, then garbage in the same write: the good one is answered first.
  const char garbage[] = {0x00, 0x00, 0x00, 0x03, '\xff', '\xff', '\xff'};
  const auto responses =
      raw_exchange(server.port(), encode_frame(submit_request(5)) + std::string(garbage, sizeof garbage));
  ASSERT_EQ(responses.size(), 2u);
  EXPECT_TRUE(responses[0].has_accepted());
  EXPECT_EQ(responses[0].request_id(), 5u);
  ASSERT_TRUE(responses[1].has_error());
  EXPECT_NE(responses[1].error().message().find("not a netmc.v1.Request"), std::string::npos);
  EXPECT_EQ(requests.load(), 1);

  // The server keeps serving other connections.
  ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
  client.send(submit_request(6));
  const auto response = client.receive(2s);
  ASSERT_TRUE(response && response->has_accepted());
}

TEST(ManagementEndpoint, OversizeFrameGetsAnErrorAndTheConnectionCloses) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  ManagementServer server(runner.io, "127.0.0.1", 0, {[](Session&, const netmc::v1::Request&) {
    ADD_FAILURE() << "no request should reach the handler";
  }});
  runner.start();
  const char header[4] = {0x7f, 0x00, 0x00, 0x00};  // 2 GiB announced
  const auto responses = raw_exchange(server.port(), std::string(header, 4));
  ASSERT_EQ(responses.size(), 1u);
  ASSERT_TRUE(responses[0].has_error());
  EXPECT_NE(responses[0].error().message().find("exceeds the 16 MiB limit"), std::string::npos)
      << responses[0].error().message();
}

TEST(ManagementEndpoint, SilentAndStalledConnectionsAreClosedButOneWithWorkUnderWayIsNot) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  ManagementLimits limits;
  limits.session.idle_timeout = 300ms;
  limits.session.frame_timeout = 300ms;
  ManagementServer server(runner.io, "127.0.0.1", 0, {[](Session& session, const netmc::v1::Request&) {
    session.mark_authenticated();
    session.hold();  // as a job of this connection would
  }}, limits);
  runner.start();
  // Nothing said at all: closed after the idle timeout.
  const auto idle = read_until_closed(server.port(), "").closed_after;
  EXPECT_GE(idle, 250ms);
  EXPECT_LT(idle, 2s);
  // Half a frame (1000 bytes announced, 10 sent): closed after the frame timeout.
  const auto stalled = read_until_closed(server.port(), std::string("\0\0\x03\xe8", 4) + std::string(10, 'x')).closed_after;
  EXPECT_GE(stalled, 250ms);
  EXPECT_LT(stalled, 2s);
  // A connection whose request started work stays open while silent.
  ManagementClient client("127.0.0.1:" + std::to_string(server.port()), 2s);
  client.send(submit_request(1));
  EXPECT_FALSE(client.receive(1s).has_value());  // nothing to say, and not closed
}

TEST(ManagementEndpoint, OneConnectionOverTheCapIsRefusedWithAMessage) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  ManagementLimits limits;
  limits.max_connections = 2;
  std::atomic<int> requests{0};
  ManagementServer server(runner.io, "127.0.0.1", 0, accept_counting(requests), limits);
  runner.start();
  const std::string endpoint = "127.0.0.1:" + std::to_string(server.port());
  ManagementClient first(endpoint, 2s), second(endpoint, 2s);
  for (auto* client : {&first, &second}) {  // both sessions exist before the third connects
    client->send(submit_request(1));
    ASSERT_TRUE(client->receive(2s).has_value());
  }
  const auto refused = raw_exchange(server.port(), encode_frame(submit_request(3)));
  ASSERT_EQ(refused.size(), 1u);
  ASSERT_TRUE(refused[0].has_error());
  EXPECT_NE(refused[0].error().message().find("server busy: 2 connections"), std::string::npos)
      << refused[0].error().message();
  EXPECT_EQ(requests.load(), 2);
}

netmc::v1::Request status_request(std::uint64_t id, const std::string& token = "") {
  netmc::v1::Request request;
  request.set_request_id(id);
  request.set_token(token);
  request.mutable_status();
  return request;
}

// Issue 26: a client that sends requests and never reads their answers once made the server
// queue them without bound (623 k status requests: 2.9 GB).
TEST(ManagementEndpoint, AClientThatNeverReadsIsNotReadFurtherAndOthersAreStillAnswered) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  const ManagementLimits limits;
  const std::string table(32 << 10, 's');  // each answer as large as a long status table
  std::atomic<int> requests{0};
  std::atomic<std::size_t> most_queued{0};
  ManagementServer server(runner.io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request& request) {
    session.mark_authenticated();
    ++requests;
    netmc::v1::Response answer;
    answer.set_request_id(request.request_id());
    answer.mutable_error()->set_message(table);
    session.send(answer);
    const auto queued = session.queued_bytes();
    if (queued > most_queued.load()) most_queued = queued;
  }}, limits);
  runner.start();

  // 1000 requests of a few bytes each: they all fit in the sockets' buffers, the writes return.
  constexpr int kRequests = 1000;
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket flooder(io);
  flooder.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  std::string flood;
  for (int i = 1; i <= kRequests; ++i) flood += encode_frame(status_request(static_cast<std::uint64_t>(i)));
  boost::asio::write(flooder, boost::asio::buffer(flood));
  std::this_thread::sleep_for(1s);  // the server reads what it will

  // What the server holds stays under the pause threshold plus one answer (32 MB without it).
  const std::size_t one_answer = table.size() + 64;
  EXPECT_LE(most_queued.load(), limits.session.pause_reading_above + one_answer)
      << requests.load() << " of " << kRequests << " requests read";
  EXPECT_LT(requests.load(), kRequests) << "every request was read although no answer was taken";

  // Another client is answered meanwhile.
  ManagementClient other("127.0.0.1:" + std::to_string(server.port()), 2s);
  other.send(status_request(5000));
  const auto answer = other.receive(2s);
  ASSERT_TRUE(answer.has_value());
  EXPECT_EQ(answer->request_id(), 5000u);

  // Once the flooder reads, every request is answered, in order: paused, not dropped.
  FrameDecoder decoder;
  std::array<char, 65536> buffer{};
  std::uint64_t next_id = 1;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (next_id <= kRequests && std::chrono::steady_clock::now() < deadline) {
    boost::system::error_code error;
    const std::size_t n = flooder.read_some(boost::asio::buffer(buffer), error);
    ASSERT_FALSE(error) << error.message() << " after " << next_id - 1 << " answers";
    decoder.feed(buffer.data(), n);
    while (auto payload = decoder.next()) {
      netmc::v1::Response response;
      ASSERT_TRUE(response.ParseFromString(*payload));
      ASSERT_EQ(response.request_id(), next_id);
      ++next_id;
    }
  }
  EXPECT_EQ(next_id, kRequests + 1u);
  EXPECT_EQ(requests.load(), kRequests + 1);
  EXPECT_LE(most_queued.load(), limits.session.pause_reading_above + one_answer);
}

// Updates pushed from other threads (a job's iterations) to a peer that never reads: the
// connection is closed at the cap, not queued without bound.
TEST(ManagementEndpoint, UpdatesPushedToAPeerThatNeverReadsCloseItAtTheCap) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  ManagementLimits limits;
  limits.session.close_above = 4u << 20;
  std::promise<std::shared_ptr<Session>> connected;
  ManagementServer server(runner.io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request&) {
    session.mark_authenticated();
    connected.set_value(session.shared_from_this());
  }}, limits);
  runner.start();
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket reader_that_never_reads(io);
  reader_that_never_reads.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  boost::asio::write(reader_that_never_reads, boost::asio::buffer(encode_frame(status_request(1))));
  auto session_future = connected.get_future();
  ASSERT_EQ(session_future.wait_for(2s), std::future_status::ready);
  const auto session = session_future.get();

  // 50 MB of updates, 256 KiB each, as fast as a job thread can send them.
  netmc::v1::Response update;
  update.mutable_error()->set_message(std::string(256 << 10, 'u'));
  std::size_t most_queued = 0;
  int sent = 0;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  for (; sent < 200 && session->open() && std::chrono::steady_clock::now() < deadline; ++sent) {
    session->send(update);
    most_queued = std::max(most_queued, session->queued_bytes());
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_FALSE(session->open()) << "all " << sent << " updates were queued; " << most_queued << " bytes at most";
  EXPECT_LE(most_queued, limits.session.close_above);
  // The peer sees the connection end (after what reached its buffers).
  reader_that_never_reads.non_blocking(true);
  boost::system::error_code error;
  std::array<char, 65536> buffer{};
  while (std::chrono::steady_clock::now() < deadline) {
    reader_that_never_reads.read_some(boost::asio::buffer(buffer), error);
    if (error && error != boost::asio::error::would_block) break;
    if (error) std::this_thread::sleep_for(5ms);
  }
  EXPECT_TRUE(error == boost::asio::error::eof || error == boost::asio::error::connection_reset) << error.message();
}

// A socket connected from `source` (any 127.x.y.z reaches a server on 127.0.0.1) that says nothing.
std::unique_ptr<boost::asio::ip::tcp::socket> silent_connection(boost::asio::io_context& io, const std::string& source,
                                                                std::uint16_t port) {
  auto socket = std::make_unique<boost::asio::ip::tcp::socket>(io);
  socket->open(boost::asio::ip::tcp::v4());
  socket->bind({boost::asio::ip::make_address(source), 0});
  socket->connect({boost::asio::ip::make_address("127.0.0.1"), port});
  socket->non_blocking(true);
  return socket;
}

// True while the server keeps the connection open (nothing to read yet, no end seen).
bool still_open(boost::asio::ip::tcp::socket& socket) {
  std::array<char, 256> buffer{};
  boost::system::error_code error;
  while (!error) socket.read_some(boost::asio::buffer(buffer), error);
  return error == boost::asio::error::would_block;
}

// Issue 26: 32 silent connections once filled the cap, and the endpoint answered "server busy"
// to everyone, the token's holder included, until the 600 s idle timeout.
TEST(ManagementEndpoint, SilentConnectionsCannotKeepATokenHolderOutAndAreClosedAtTheDeadline) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  ManagementLimits limits;
  limits.session.authentication_timeout = 3s;
  const std::string token = "0123456789abcdef-lab";
  ManagementServer server(runner.io, "127.0.0.1", 0, {[&](Session& session, const netmc::v1::Request& request) {
    netmc::v1::Response response;
    response.set_request_id(request.request_id());
    if (request.token() != token) {
      response.mutable_error()->set_message("unauthenticated");
      session.send(response);
      session.close();
      return;
    }
    session.mark_authenticated();
    response.mutable_status();
    session.send(response);
  }}, limits);
  runner.start();
  boost::asio::io_context io;
  std::vector<std::unique_ptr<boost::asio::ip::tcp::socket>> from_one_host, from_many_hosts;
  const auto opened = std::chrono::steady_clock::now();
  for (int i = 0; i < 40; ++i) from_one_host.push_back(silent_connection(io, "127.0.0.1", server.port()));
  for (int host = 2; host <= 40; ++host) {
    from_many_hosts.push_back(silent_connection(io, "127.0.0." + std::to_string(host), server.port()));
  }
  std::this_thread::sleep_for(300ms);  // all accepted by the server

  const auto asked = std::chrono::steady_clock::now();
  ManagementClient holder("127.0.0.1:" + std::to_string(server.port()), 2s);
  holder.send(status_request(7, token));
  const auto answer = holder.receive(2s);
  const auto waited = std::chrono::steady_clock::now() - asked;
  ASSERT_TRUE(answer.has_value());
  EXPECT_TRUE(answer->has_status()) << answer->ShortDebugString();
  EXPECT_LT(waited, 1s) << "the token's holder waited for the silent connections' deadline";

  // What the silent ones still hold: within the unauthenticated share, and per address.
  const auto open_from_one = std::count_if(from_one_host.begin(), from_one_host.end(), [](auto& s) { return still_open(*s); });
  const auto open_from_many = std::count_if(from_many_hosts.begin(), from_many_hosts.end(), [](auto& s) { return still_open(*s); });
  EXPECT_LE(static_cast<std::size_t>(open_from_one), limits.max_unauthenticated_per_address);
  EXPECT_LE(static_cast<std::size_t>(open_from_one + open_from_many), limits.max_unauthenticated);

  // Every silent connection is closed by the deadline (and a quarter second of its timer).
  std::size_t open = 0;
  do {
    std::this_thread::sleep_for(100ms);
    open = 0;
    for (auto* group : {&from_one_host, &from_many_hosts}) {
      for (auto& socket : *group) open += still_open(*socket) ? 1 : 0;
    }
  } while (open > 0 && std::chrono::steady_clock::now() - opened < 8s);
  EXPECT_EQ(open, 0u) << "silent connections still open 8 s after they connected";
  // The token's holder stays.
  holder.send(status_request(8, token));
  const auto again = holder.receive(2s);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->request_id(), 8u);
}

TEST(AccessToken, AcceptsOnlyTheTokenOfItsFile) {
  const auto path = std::filesystem::temp_directory_path() / "netmc_token_test";
  const auto write = [&](const std::string& text) {
    std::ofstream file(path, std::ios::trunc);
    file << text;
  };
  write("  0123456789abcdef-lab \n");
  const AccessToken token = AccessToken::from_file(path.string());
  EXPECT_TRUE(token.accepts("0123456789abcdef-lab"));
  EXPECT_FALSE(token.accepts("0123456789abcdef-la"));
  EXPECT_FALSE(token.accepts("0123456789abcdef-lab2"));
  EXPECT_FALSE(token.accepts(""));
  write("short\n");
  EXPECT_THROW(AccessToken::from_file(path.string()), std::invalid_argument);
  write("sixteen chars but spaces\n");
  EXPECT_THROW(AccessToken::from_file(path.string()), std::invalid_argument);
  std::filesystem::remove(path);
  EXPECT_THROW(AccessToken::from_file(path.string()), std::invalid_argument);
}

TEST(ManagementServer, BadBindAddress) {
  boost::asio::io_context io;
  EXPECT_THROW(ManagementServer(io, "not-an-address", 0, {}), std::invalid_argument);
  ManagementServer first(io, "127.0.0.1", 0, {});
  try {  // the port is taken by a listening socket
    ManagementServer second(io, "127.0.0.1", first.port(), {});
    FAIL() << "bound a port in use";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:" + std::to_string(first.port())), std::string::npos)
        << error.what();
  }
}

TEST(ManagementClient, MalformedHostPort) {
  for (const std::string bad : {"", "localhost", "localhost:", ":7400", "localhost:http", "localhost:0",
                                "localhost:65536", "localhost:-1", "::1:7400", "[::1]"}) {
    try {
      ManagementClient client(bad, 1s);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& error) {
      EXPECT_EQ(std::string(error.what()), "--server: expected HOST:PORT, got '" + bad + "'");
    }
  }
}

TEST(ManagementClient, ConnectionRefusedNamesTheServer) {
  // A port nobody listens on: take a free one, then close it.
  boost::asio::io_context io;
  boost::asio::ip::tcp::acceptor probe(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
  const auto port = probe.local_endpoint().port();
  probe.close();
  const std::string where = "127.0.0.1:" + std::to_string(port);
  try {
    ManagementClient client(where, 1s);
    FAIL() << "connected to a closed port";
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), "server " + where + ": connection refused: no netmc-server listens there (start "
                                         "one with `netmc-server --listen " + where +
                                         "`, or name another with --server or NETMC_SERVER)");
  }
}

TEST(ManagementClient, Ipv6Loopback) {
  IoThread runner;  // first: everything holding a Session goes before the io_context
  boost::system::error_code error;
  boost::asio::ip::tcp::acceptor probe(runner.io);
  probe.open(boost::asio::ip::tcp::v6(), error);
  if (!error) probe.bind({boost::asio::ip::make_address("::1"), 0}, error);
  if (error) GTEST_SKIP() << "no IPv6 loopback here";
  probe.close();
  ManagementServer server(runner.io, "::1", 0, {[](Session& session, const netmc::v1::Request& request) {
    netmc::v1::Response response;
    response.set_request_id(request.request_id());
    response.mutable_nodes();
    session.send(response);
  }});
  runner.start();
  ManagementClient client("[::1]:" + std::to_string(server.port()), 2s);
  netmc::v1::Request request;
  request.set_request_id(9);
  request.mutable_nodes();
  client.send(request);
  const auto response = client.receive(2s);
  ASSERT_TRUE(response && response->has_nodes());
  EXPECT_EQ(response->request_id(), 9u);
}

}  // namespace
}  // namespace netmc::management
