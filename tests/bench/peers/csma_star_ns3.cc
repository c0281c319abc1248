// csma_star_ns3.cc - IEEE 802.15.4 unslotted CSMA-CA saturation throughput on a star,
// on ns-3 3.37's LR-WPAN model (own code).
//   One PAN coordinator (short address 00:00) at the origin, n leaves (00:01 ... ) on a circle
//   of radius 1 m; LrWpanHelper's channel (SingleModelSpectrumChannel, LogDistance loss,
//   constant-speed delay), ConstantPositionMobilityModel. Every leaf is saturated: its first
//   MCPS-DATA.request is made at t = i microseconds (leaf i = 1..n) and every
//   MCPS-DATA.confirm (any status) immediately requests the next acknowledged unicast to 00:00.
//   Counts are taken over [warmup, warmup + seconds) of simulated time.
//   --n=10 --payload=20 --seconds=20 --seed=1 --warmup=1
//   --collisions=capture (default: ns-3 as is; a receiver locked on the first frame keeps it
//                         unless the chunk error model, fed with the SINR, corrupts it)
//               =destroy (diagnostic: a post-reception error model also drops every frame that
//                         overlapped another transmission, i.e. no capture)
// Prints one RESULT line, one PARAMS line (timing constants read from ns-3 and measured on
// the run) and one CHECK line (link budget at 1 m and 2 m: SNR and noise-only frame error).
#include "common.h"
#include "ns3/core-module.h"
#include "ns3/lr-wpan-module.h"
#include "ns3/mobility-module.h"
#include "ns3/network-module.h"
#include "ns3/propagation-module.h"
#include "ns3/spectrum-module.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace ns3;
using namespace anchors;

static const uint16_t kPanId = 0x0005;
static const uint32_t kChannel = 11; // 2.4 GHz O-QPSK, the LR-WPAN PHY default

// One radio: the coordinator is index 0, leaf i is index i.
struct Radio {
    Ptr<LrWpanNetDevice> dev;
    Time txBegin, txEnd;       // current / last own transmission
    bool overlapped = false;   // did another transmission overlap it (at the transmitters)?
    bool ownAck = false;       // leaf: the ACK of its last data frame arrived (within wait)
    bool foreignAck = false;   // leaf: another frame's ACK arrived while it waited for its own
    Time ackEnd;               // leaf: when that ACK ended
    int lastDeliveredSeq = -1; // coordinator's view: last delivered sequence number from it
};

struct Stats {
    uint64_t delivered = 0, duplicates = 0, success = 0, caf = 0, noAck = 0, other = 0;
    uint64_t attempts = 0, overlappedData = 0, deliveredAfterOverlap = 0;
    uint64_t falseAcks = 0; // SUCCESS confirmed by another leaf's ACK with the same sequence number
    uint32_t dataPsdu = 0, ackPsdu = 0;
    Time dataAir, ackAir;                          // PPDU airtimes seen on the PHY
    Time turnaround = Time::Max();                 // coordinator: data RX end -> ACK TX begin
    Time afterAck = Time::Max();                   // leaf: ACK RX end -> next data TX begin
    Time afterNoAck = Time::Max();                 // leaf: no ACK at all: TX end -> next TX begin
    Time afterForeignAck = Time::Max();            // leaf: foreign ACK end -> next TX begin
    Time ackEndAfterData = Time::Max();            // leaf: data TX end -> ACK RX end
    Time ifsAfterSuccess;                          // from the MAC's IfsEnd trace
    uint64_t ifsEvents = 0;
};

static std::vector<Radio> g_radio;
static Stats g_st;
static Time g_from, g_to;
static uint32_t g_payload;

// Drops every received frame whose transmission overlapped another one (no capture).
class OverlapErrorModel : public ErrorModel {
  private:
    bool DoCorrupt(Ptr<Packet> p) override {
        LrWpanMacHeader hdr;
        p->PeekHeader(hdr);
        if (hdr.IsAcknowledgment()) return g_radio[0].overlapped;
        uint8_t buf[2];
        hdr.GetShortSrcAddr().CopyTo(buf);
        const uint32_t idx = ((uint32_t)buf[0] << 8) | buf[1];
        return idx < g_radio.size() && g_radio[idx].overlapped;
    }
    void DoReset() override {}
};

static bool Counting() {
    const Time now = Simulator::Now();
    return now >= g_from && now < g_to;
}

static std::vector<int> g_leafSeq; // sequence number of each leaf's frame on air / last sent

static McpsDataRequestParams LeafRequest() {
    McpsDataRequestParams params;
    params.m_srcAddrMode = SHORT_ADDR;
    params.m_dstAddrMode = SHORT_ADDR;
    params.m_dstPanId = kPanId;
    params.m_dstAddr = Mac16Address("00:00");
    params.m_msduHandle = 0;
    params.m_txOptions = TX_OPTION_ACK;
    return params;
}

static void SendNext(uint32_t leaf) {
    g_radio[leaf].dev->GetMac()->McpsDataRequest(LeafRequest(), Create<Packet>(g_payload));
}

static void LeafConfirm(uint32_t leaf, McpsDataConfirmParams params) {
    if (Counting()) {
        switch (params.m_status) {
        case IEEE_802_15_4_SUCCESS:
            ++g_st.success;
            if (g_radio[leaf].lastDeliveredSeq != g_leafSeq[leaf]) ++g_st.falseAcks;
            break;
        case IEEE_802_15_4_CHANNEL_ACCESS_FAILURE: ++g_st.caf; break;
        case IEEE_802_15_4_NO_ACK: ++g_st.noAck; break;
        default: ++g_st.other; break;
        }
    }
    SendNext(leaf); // saturation: the next frame is pending at once
}

static void CoordIndication(McpsDataIndicationParams params, Ptr<Packet> p) {
    uint8_t buf[2];
    params.m_srcAddr.CopyTo(buf);
    const uint32_t leaf = ((uint32_t)buf[0] << 8) | buf[1];
    NS_ABORT_MSG_IF(leaf == 0 || leaf >= g_radio.size(), "unexpected source");
    Radio& r = g_radio[leaf];
    const bool duplicate = (r.lastDeliveredSeq == params.m_dsn);
    r.lastDeliveredSeq = params.m_dsn;
    if (!Counting()) return;
    ++g_st.delivered;
    if (duplicate) ++g_st.duplicates;
    if (r.overlapped) ++g_st.deliveredAfterOverlap;
}

// Overlap is judged at the transmitters (propagation delay of a few ns ignored).
static void TxBegin(uint32_t idx, Ptr<const Packet> p) {
    const Time now = Simulator::Now();
    Radio& me = g_radio[idx];
    if (idx != 0 && me.txEnd.IsStrictlyPositive()) {
        if (me.ownAck)
            g_st.afterAck = std::min(g_st.afterAck, now - me.ackEnd);
        else if (me.foreignAck)
            g_st.afterForeignAck = std::min(g_st.afterForeignAck, now - me.ackEnd);
        else
            g_st.afterNoAck = std::min(g_st.afterNoAck, now - me.txEnd);
    }
    me.txBegin = now;
    me.overlapped = false;
    me.ownAck = me.foreignAck = false;
    for (uint32_t j = 0; j < g_radio.size(); ++j) {
        if (j == idx) continue;
        Radio& other = g_radio[j];
        if (other.txBegin <= now && other.txEnd > now) { // still on air
            other.overlapped = true;
            me.overlapped = true;
        }
    }
    me.txEnd = Time::Max(); // fixed at TxEnd
    if (idx != 0 && Counting()) ++g_st.attempts;
}

static void TxEnd(uint32_t idx, Ptr<const Packet> p) {
    Radio& me = g_radio[idx];
    me.txEnd = Simulator::Now();
    const Time air = me.txEnd - me.txBegin;
    if (idx == 0) {
        g_st.ackPsdu = p->GetSize();
        g_st.ackAir = air;
    } else {
        g_st.dataPsdu = p->GetSize();
        g_st.dataAir = air;
        if (me.overlapped && Counting()) ++g_st.overlappedData;
    }
}

// Coordinator: end of a cleanly received data frame -> its ACK's TX begin (RX->TX turnaround).
static Time g_coordRxEnd;
static void CoordRxEnd(Ptr<const Packet> p, double sinr) { g_coordRxEnd = Simulator::Now(); }
static void CoordTxBeginAck(Ptr<const Packet> p) {
    g_st.turnaround = std::min(g_st.turnaround, Simulator::Now() - g_coordRxEnd);
}

// Leaf: the MAC accepted (PHY-correct) ACK of its own pending frame -> gaps to its next frame.
static void LeafMacTx(uint32_t leaf, Ptr<const Packet> p) {
    LrWpanMacHeader hdr;
    p->PeekHeader(hdr);
    g_leafSeq[leaf] = hdr.GetSeqNum();
}
static void LeafMacRx(uint32_t leaf, Ptr<const Packet> p) {
    LrWpanMacHeader hdr;
    p->PeekHeader(hdr);
    Radio& me = g_radio[leaf];
    const Time now = Simulator::Now();
    const Time ackWait = MicroSeconds(16 * me.dev->GetMac()->GetMacAckWaitDuration());
    // Only the first ACK inside the wait after its own data frame counts (the MAC reacts to it).
    if (!hdr.IsAcknowledgment() || me.txEnd == Time::Max() || now - me.txEnd > ackWait ||
        me.ownAck || me.foreignAck)
        return;
    me.ackEnd = now;
    if (hdr.GetSeqNum() == g_leafSeq[leaf]) {
        me.ownAck = true;
        g_st.ackEndAfterData = std::min(g_st.ackEndAfterData, now - me.txEnd);
    } else {
        me.foreignAck = true;
    }
}
static void IfsEnd(Time ifs) {
    g_st.ifsAfterSuccess = ifs;
    ++g_st.ifsEvents;
}

static void StartCoordinator(Ptr<LrWpanMac> mac) {
    MlmeStartRequestParams params;
    params.m_panCoor = true;
    params.m_PanId = kPanId;
    params.m_bcnOrd = 15; // nonbeacon-enabled PAN: unslotted CSMA-CA
    params.m_sfrmOrd = 15;
    params.m_logCh = kChannel;
    params.m_logChPage = 0;
    mac->MlmeStartRequest(params);
}

static Ptr<MobilityModel> At(double x_m, double y_m) {
    Ptr<ConstantPositionMobilityModel> m = CreateObject<ConstantPositionMobilityModel>();
    m->SetPosition(Vector(x_m, y_m, 0));
    return m;
}

// SNR and noise-only PER (ns-3's LrWpanErrorModel) of one data PPDU at a given distance.
static void LinkCheck(double distance_m, uint32_t ppduBytes, double& snr_db, double& per) {
    LrWpanSpectrumValueHelper psd;
    Ptr<SpectrumValue> tx = psd.CreateTxPowerSpectralDensity(0.0, kChannel); // phyTransmitPower 0
    Ptr<SpectrumValue> noise = psd.CreateNoisePowerSpectralDensity(kChannel);
    Ptr<LogDistancePropagationLossModel> loss = CreateObject<LogDistancePropagationLossModel>();
    const double rx_dbm = loss->CalcRxPower(0.0, At(0, 0), At(distance_m, 0));
    const double snr = LrWpanSpectrumValueHelper::TotalAvgPower(tx, kChannel) *
                       std::pow(10.0, rx_dbm / 10.0) /
                       LrWpanSpectrumValueHelper::TotalAvgPower(noise, kChannel);
    snr_db = 10 * std::log10(snr);
    Ptr<LrWpanErrorModel> em = CreateObject<LrWpanErrorModel>();
    per = 1.0 - em->GetChunkSuccessRate(snr, ppduBytes * 8);
}

static double Us(Time t) { return t == Time::Max() ? -1.0 : t.GetNanoSeconds() / 1000.0; }

int main(int argc, char** argv) {
    Args args(argc, argv);
    const uint32_t n = (uint32_t)args.num("n", 10);
    g_payload = (uint32_t)args.num("payload", 20);
    const double seconds = args.num("seconds", 20);
    const double warmup = args.num("warmup", 1);
    RngSeedManager::SetSeed(1);
    RngSeedManager::SetRun((uint64_t)args.num("seed", 1));
    g_from = Seconds(warmup);
    g_to = Seconds(warmup + seconds);
    const std::string collisions = args.str("collisions", "capture");
    NS_ABORT_MSG_IF(collisions != "capture" && collisions != "destroy", "--collisions=capture|destroy");

    NodeContainer nodes;
    nodes.Create(n + 1);
    LrWpanHelper lrWpan; // SingleModelSpectrumChannel + LogDistance loss + constant-speed delay
    NetDeviceContainer devs = lrWpan.Install(nodes);
    g_radio.resize(n + 1);
    g_leafSeq.assign(n + 1, -1);
    for (uint32_t i = 0; i <= n; ++i) {
        Ptr<LrWpanNetDevice> dev = DynamicCast<LrWpanNetDevice>(devs.Get(i));
        g_radio[i].dev = dev;
        const double angle = 2 * M_PI * (i == 0 ? 0 : i - 1) / std::max(n, 1u);
        Ptr<MobilityModel> mob = i == 0 ? At(0, 0) : At(std::cos(angle), std::sin(angle));
        nodes.Get(i)->AggregateObject(mob);
        dev->GetPhy()->SetMobility(mob);
        uint8_t buf[2] = {(uint8_t)(i >> 8), (uint8_t)(i & 0xff)};
        Mac16Address addr;
        addr.CopyFrom(buf);
        dev->SetAddress(addr);
        Ptr<LrWpanMac> mac = dev->GetMac();
        mac->SetPanId(kPanId);
        mac->SetMacMaxFrameRetries(3);
        Ptr<LrWpanCsmaCa> csma = dev->GetCsmaCa();
        csma->SetMacMaxBE(5); // before MinBE: SetMacMinBE asserts MinBE <= MaxBE
        csma->SetMacMinBE(3);
        csma->SetMacMaxCSMABackoffs(4);
        Ptr<LrWpanPhy> phy = dev->GetPhy();
        if (collisions == "destroy") phy->SetPostReceptionErrorModel(CreateObject<OverlapErrorModel>());
        phy->TraceConnectWithoutContext("PhyTxBegin", MakeBoundCallback(&TxBegin, i));
        phy->TraceConnectWithoutContext("PhyTxEnd", MakeBoundCallback(&TxEnd, i));
        if (i == 0) {
            mac->SetMcpsDataIndicationCallback(MakeCallback(&CoordIndication));
            phy->TraceConnectWithoutContext("PhyRxEnd", MakeCallback(&CoordRxEnd));
            phy->TraceConnectWithoutContext("PhyTxBegin", MakeCallback(&CoordTxBeginAck));
            Simulator::ScheduleWithContext(i, Seconds(0), &StartCoordinator, mac);
        } else {
            mac->SetMcpsDataConfirmCallback(MakeBoundCallback(&LeafConfirm, i));
            mac->TraceConnectWithoutContext("IfsEnd", MakeCallback(&IfsEnd));
            mac->TraceConnectWithoutContext("MacTx", MakeBoundCallback(&LeafMacTx, i));
            mac->TraceConnectWithoutContext("MacRx", MakeBoundCallback(&LeafMacRx, i));
            Simulator::ScheduleWithContext(i, MicroSeconds(i), &SendNext, i);
        }
    }
    Ptr<LrWpanMac> mac1 = g_radio[std::min(1u, n)].dev->GetMac();
    Ptr<LrWpanCsmaCa> csma1 = g_radio[std::min(1u, n)].dev->GetCsmaCa();
    Ptr<LrWpanPhy> phy1 = g_radio[std::min(1u, n)].dev->GetPhy();

    const double w0 = nowSec();
    Simulator::Stop(g_to);
    Simulator::Run();
    const double wall_s = nowSec() - w0;

    const uint32_t dataPpdu = (uint32_t)std::lround(g_st.dataAir.GetMicroSeconds() / 32.0);
    const uint32_t ackPpdu = (uint32_t)std::lround(g_st.ackAir.GetMicroSeconds() / 32.0);
    const double symbol_us = 1e6 / phy1->GetDataOrSymbolRate(false);
    const double sym = symbol_us;
    std::printf("RESULT n=%u payload=%u seconds=%g delivered_per_s=%.2f success_confirms_per_s=%.2f "
                "channel_access_failures=%llu no_ack=%llu psdu_bytes=%u ppdu_bytes=%u "
                "unique_per_s=%.2f duplicates=%llu tx_attempts=%llu overlapped_data_tx=%llu "
                "delivered_after_overlap=%llu false_acks=%llu other_confirms=%llu seed=%llu "
                "collisions=%s wall_s=%.2f\n",
                n, g_payload, seconds, g_st.delivered / seconds, g_st.success / seconds,
                (unsigned long long)g_st.caf, (unsigned long long)g_st.noAck, g_st.dataPsdu,
                dataPpdu, (g_st.delivered - g_st.duplicates) / seconds,
                (unsigned long long)g_st.duplicates, (unsigned long long)g_st.attempts,
                (unsigned long long)g_st.overlappedData,
                (unsigned long long)g_st.deliveredAfterOverlap, (unsigned long long)g_st.falseAcks,
                (unsigned long long)g_st.other,
                (unsigned long long)args.num("seed", 1), collisions.c_str(), wall_s);
    // Measured minima: afterAck = IFS + CCA + RX->TX turnaround (backoff 0);
    // afterNoAck = macAckWaitDuration + CCA + turnaround (the retry restarts CSMA, no IFS).
    const double cca_sym = (Us(g_st.afterAck) - Us(g_st.ifsAfterSuccess) - Us(g_st.turnaround)) / sym;
    std::printf("PARAMS symbol_us=%g bit_rate_bps=%g unit_backoff_symbols=%llu min_be=%u max_be=%u "
                "max_csma_backoffs=%u max_frame_retries=%u turnaround_symbols=%u "
                "ack_wait_symbols=%llu sifs_symbols=%u lifs_symbols=%u max_sifs_frame_bytes=%u "
                "shr_symbols=%llu symbols_per_octet=%g mac_overhead_bytes=%u phy_header_bytes=%u "
                "ack_psdu_bytes=%u ack_ppdu_bytes=%u data_air_us=%g ack_air_us=%g "
                "measured_rx_to_tx_us=%.3f measured_ack_end_after_data_us=%.3f "
                "measured_ifs_after_success_symbols=%g ifs_events=%llu "
                "measured_min_ack_end_to_next_tx_us=%.3f measured_cca_symbols=%.2f "
                "measured_min_noack_tx_end_to_retry_us=%.3f "
                "measured_min_foreign_ack_end_to_retry_us=%.3f\n",
                symbol_us, phy1->GetDataOrSymbolRate(true),
                (unsigned long long)csma1->GetUnitBackoffPeriod(), csma1->GetMacMinBE(),
                csma1->GetMacMaxBE(), csma1->GetMacMaxCSMABackoffs(),
                mac1->GetMacMaxFrameRetries(), LrWpanPhy::aTurnaroundTime,
                (unsigned long long)mac1->GetMacAckWaitDuration(), mac1->m_macSIFSPeriod,
                mac1->m_macLIFSPeriod, LrWpanMac::aMaxSIFSFrameSize,
                (unsigned long long)phy1->GetPhySHRDuration(), phy1->GetPhySymbolsPerOctet(),
                g_st.dataPsdu - g_payload, dataPpdu - g_st.dataPsdu, g_st.ackPsdu, ackPpdu,
                (double)g_st.dataAir.GetMicroSeconds(), (double)g_st.ackAir.GetMicroSeconds(),
                Us(g_st.turnaround), Us(g_st.ackEndAfterData), Us(g_st.ifsAfterSuccess) / sym,
                (unsigned long long)g_st.ifsEvents, Us(g_st.afterAck), cca_sym,
                Us(g_st.afterNoAck), Us(g_st.afterForeignAck));
    double snr1_db, per1, snr2_db, per2;
    LinkCheck(1.0, dataPpdu, snr1_db, per1);
    LinkCheck(2.0, dataPpdu, snr2_db, per2);
    std::printf("CHECK snr_1m_db=%.1f noise_per_1m=%.3g snr_2m_db=%.1f noise_per_2m=%.3g\n",
                snr1_db, per1, snr2_db, per2);
    g_radio.clear();
    Simulator::Destroy();
    return 0;
}
