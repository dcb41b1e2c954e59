//! x^p for positive x by a table-driven log₂ and exp₂: the law of a tabulated (log-log interpolated)
//! density, about half the operations of `exp(p·ln x)` by [`vmath`](super::vmath)'s formulas and no
//! division.
//!
//! Like [`vmath`](super::vmath)'s functions, [`pow_positive`] is a branch-free scalar formula (`+ − ×`,
//! comparisons, bit operations and loads from constant tables; no call, no fused multiply-add; a
//! `PowerFrom` is prepared once with one): inside
//! [`vmath::map`](super::vmath::map) it is compiled for AVX-512, AVX2 and SSE2 (the tables read by gathers
//! or lane by lane), and every instruction set gives the same bits.
//!
//! # Formula
//! x = 2^k·m with m ∈ [1, 2) from the bits of x; the top 9 bits of m's fraction name its cell
//! c_j = 1 + j/512 (j = 0…511), so that m − c_j is exact and r = (m − c_j)·(1/c_j) ∈ [0, 2⁻⁹). Then
//! ```text
//! u = log₂ x = k + log₂ c_j + log₂(1 + r),    log₂(1 + r) = (r − r²/2 + … + r⁵/5)/ln 2   (truncation < 1.4·10⁻¹⁷)
//! τ = 128 p·u,   n = round(τ),   σ = τ − n ∈ [−½, ½] (exact),   n = 128 e + i (i = 0…127)
//! x^p = 2^(τ/128) = 2^e · 2^(i/128) · 2^(σ/128),    2^(σ/128) = 1 + q(σ), q of degree 5 (truncation < 6·10⁻¹⁹)
//! ```
//! log₂ c_j and 2^(i/128) are tables of the correctly rounded values (`scripts/pow_tables.py`, mpmath at 60
//! digits); 1/c_j is one correctly rounded division, done when compiling. 2^e is applied as two exact
//! powers of two, so that a subnormal result is rounded once; in [`pow_positive`] t is clamped to
//! [−1080, 1025] first (a `PowerFrom` keeps |t| ≤ 2000 by construction and needs no clamp), which
//! makes a result beyond the range 0 or +∞ by the same arithmetic. At x = 1 (a node of a table), u = 0 and
//! x^p = 1 exactly, for every p.
//!
//! # Accuracy
//! The table-driven reduction follows P. T. P. Tang, "Table-driven implementation of the exponential
//! function in IEEE floating-point arithmetic", ACM TOMS 15 (1989) 144–157, and "Table-driven
//! implementation of the logarithm function …", ACM TOMS 16 (1990) 378–400. With ε = 2⁻⁵²: the error of u
//! is at most 0.6 ε + 2|u| ε (the rounding of log₂ c_j, the polynomial's truncation and rounding, the two sums), so that of
//! t = p·u at most 0.6|p| ε + 2.5|t| ε; 2^t adds 1.02 ε (the table entry, the sum T + T·q) and turns an
//! error δ of t into ln 2·δ relative. Relative to x^p, in all:
//! ```text
//! |pow_positive(x, p) − x^p| ≤ (1.1 + 0.42|p| + 1.75|t|)·ε·x^p,   t = p·log₂ x
//! ```
//! for a normal result; [`POW_ERROR`] states it with margin and the tests check it against libm's `powf`
//! over about 10⁶ arguments.

/// Where [`pow_positive`] may be relied on, relative to x^p, in units of ε = 2⁻⁵² (see the module docs):
/// `(c₀, c_p, c_t)` in |error| ≤ (c₀ + c_p|p| + c_t|t|)·ε·x^p, t = p·log₂ x, for a normal result.
pub const POW_ERROR: (f64, f64, f64) = (1.5, 0.5, 2.0);

/// The bits of 1.0: the exponent field of [1, 2).
const ONE: u64 = 0x3ff0_0000_0000_0000;
/// The fraction field of an f64.
const FRACTION: u64 = 0x000f_ffff_ffff_ffff;
/// The top 9 bits of the fraction: the cell of m.
const CELL: u64 = 0x000f_f800_0000_0000;

/// log₂(1 + j/512), correctly rounded (bits), j = 0…511.
#[rustfmt::skip]
const LOG2_CELL: [u64; 512] = [
    0x0000000000000000, 0x3f670f83ff0a7565, 0x3f7709c46d7aac77, 0x3f8143068125dd0e,
    0x3f86fe50b6ef0851, 0x3f8cb6c3abd14559, 0x3f91363117a97b0c, 0x3f940f9786685d29,
    0x3f96e79685c2d22a, 0x3f99be2f7749acc2, 0x3f9c9363ba850f86, 0x3f9f6734acf8695a,
    0x3fa11cd1d5133413, 0x3fa2855905ca70f6, 0x3fa3ed3094685a26, 0x3fa554592bb8cd58,
    0x3fa6bad3758efd87, 0x3fa820a01ac754cb, 0x3fa985bfc3495194, 0x3faaea3316095f72,
    0x3fac4dfab90aab5f, 0x3fadb1175160f3b0, 0x3faf1389833253a0, 0x3fb03aa8f8dc854c,
    0x3fb0eb389fa29f9b, 0x3fb19b74069f5f0a, 0x3fb24b5b7e135a3d, 0x3fb2faef55ccb372,
    0x3fb3aa2fdd27f1c3, 0x3fb4591d6310d85a, 0x3fb507b836033bb7, 0x3fb5b600a40bd4f3,
    0x3fb663f6fac91316, 0x3fb7119b876bea86, 0x3fb7beee96b8a281, 0x3fb86bf07507a0c7,
    0x3fb918a16e46335b, 0x3fb9c501cdf75872, 0x3fba7111df348494, 0x3fbb1cd1ecae66e7,
    0x3fbbc84240adabba, 0x3fbc73632513bd4f, 0x3fbd1e34e35b82da, 0x3fbdc8b7c49a1ddb,
    0x3fbe72ec117fa5b2, 0x3fbf1cd21257e18c, 0x3fbfc66a0f0b00a5, 0x3fc037da278f2870,
    0x3fc08c588cda79e4, 0x3fc0e0b05ac848ed, 0x3fc134e1b489062e, 0x3fc188ecbd1d16be,
    0x3fc1dcd197552b7b, 0x3fc2309065d29791, 0x3fc284294b07a640, 0x3fc2d79c6937efdd,
    0x3fc32ae9e278ae1a, 0x3fc37e11d8b10f89, 0x3fc3d1146d9a8a64, 0x3fc423f1c2c12ea2,
    0x3fc476a9f983f74d, 0x3fc4c93d33151b24, 0x3fc51bab907a5c8a, 0x3fc56df5328d58c5,
    0x3fc5c01a39fbd688, 0x3fc6121ac74813cf, 0x3fc663f6fac91316, 0x3fc6b5aef4aae7dc,
    0x3fc70742d4ef027f, 0x3fc758b2bb6c7b76, 0x3fc7a9fec7d05ddf, 0x3fc7fb27199df16d,
    0x3fc84c2bd02f03b3, 0x3fc89d0d0ab430cd, 0x3fc8edcae8352b6c, 0x3fc93e6587910444,
    0x3fc98edd077e70df, 0x3fc9df31868c11d5, 0x3fca2f632320b86b, 0x3fca7f71fb7bab9d,
    0x3fcacf5e2db4ec94, 0x3fcb1f27d7bd7a80, 0x3fcb6ecf175f95e9, 0x3fcbbe540a3f036f,
    0x3fcc0db6cdd94dee, 0x3fcc5cf77f860826, 0x3fccac163c770dc9, 0x3fccfb1321b8c400,
    0x3fcd49ee4c325970, 0x3fcd98a7d8a605a7, 0x3fcde73fe3b1480f, 0x3fce35b689cd2655,
    0x3fce840be74e6a4d, 0x3fced2401865df52, 0x3fcf205339208f27, 0x3fcf6e456567fe55,
    0x3fcfbc16b902680a, 0x3fd004e3a7c97cbd, 0x3fd02baba24d0664, 0x3fd0526359bab1b3,
    0x3fd0790adbb03009, 0x3fd09fa235ba2020, 0x3fd0c62975542a8f, 0x3fd0eca0a7e91e0b,
    0x3fd11307dad30b76, 0x3fd1395f1b5b61a6, 0x3fd15fa676bb08ff, 0x3fd185ddfa1a7ed0,
    0x3fd1ac05b291f070, 0x3fd1d21dad295632, 0x3fd1f825f6d88e13, 0x3fd21e1e9c877639,
    0x3fd24407ab0e073a, 0x3fd269e12f346e2c, 0x3fd28fab35b32683, 0x3fd2b565cb3313b6,
    0x3fd2db10fc4d9aaf, 0x3fd300acd58cbb10, 0x3fd32639636b2836, 0x3fd34bb6b2546218,
    0x3fd37124cea4cded, 0x3fd39683c4a9ce9a, 0x3fd3bbd3a0a1dcfb, 0x3fd3e1146ebc9ff2,
    0x3fd406463b1b0449, 0x3fd42b6911cf5465, 0x3fd4507cfedd4fc4, 0x3fd475820e3a4251,
    0x3fd49a784bcd1b8b, 0x3fd4bf5fc36e8577, 0x3fd4e43880e8fb6a, 0x3fd509028ff8e0a2,
    0x3fd52dbdfc4c96b3, 0x3fd5526ad18493ce, 0x3fd577091b3378cb, 0x3fd59b98e4de271c,
    0x3fd5c01a39fbd688, 0x3fd5e48d25f62ab9, 0x3fd608f1b42948ae, 0x3fd62d47efe3ebee,
    0x3fd6518fe4677ba7, 0x3fd675c99ce81f92, 0x3fd699f5248cd4b8, 0x3fd6be12866f820d,
    0x3fd6e221cd9d0cde, 0x3fd7062305156d1d, 0x3fd72a1637cbc183, 0x3fd74dfb70a66388,
    0x3fd771d2ba7efb3c, 0x3fd7959c202292f1, 0x3fd7b957ac51aac4, 0x3fd7dd0569c04bff,
    0x3fd800a563161c54, 0x3fd82437a2ee70f7, 0x3fd847bc33d8618e, 0x3fd86b332056db01,
    0x3fd88e9c72e0b226, 0x3fd8b1f835e0b642, 0x3fd8d54673b5c372, 0x3fd8f88736b2d4e8,
    0x3fd91bba891f1709, 0x3fd93ee07535f967, 0x3fd961f90527409c, 0x3fd98504431717fc,
    0x3fd9a802391e232f, 0x3fd9caf2f1498fa4, 0x3fd9edd6759b25e0, 0x3fda10acd0095ab4,
    0x3fda33760a7f6051, 0x3fda56322edd3731, 0x3fda78e146f7bef4, 0x3fda9b835c98c70a,
    0x3fdabe18797f1f49, 0x3fdae0a0a75ea862, 0x3fdb031befe06434, 0x3fdb258a5ca28608,
    0x3fdb47ebf73882a1, 0x3fdb6a40c92b203f, 0x3fdb8c88dbf8867a, 0x3fdbaec439144dfd,
    0x3fdbd0f2e9e79031, 0x3fdbf314f7d0f6ba, 0x3fdc152a6c24cae6, 0x3fdc3733502d04f8,
    0x3fdc592fad295b56, 0x3fdc7b1f8c4f51a4, 0x3fdc9d02f6ca47b4, 0x3fdcbed9f5bb886a,
    0x3fdce0a4923a587d, 0x3fdd0262d554051c, 0x3fdd2414c80bf27d, 0x3fdd45ba735baa4f,
    0x3fdd6753e032ea0f, 0x3fdd88e11777b149, 0x3fddaa6222064fb9, 0x3fddcbd708b17359,
    0x3fdded3fd442364c, 0x3fde0e9c8d782cbd, 0x3fde2fed3d097298, 0x3fde5131eba2b931,
    0x3fde726aa1e754d2, 0x3fde939768714a32, 0x3fdeb4b847d15bce, 0x3fded5cd488f1732,
    0x3fdef6d67328e220, 0x3fdf17d3d01407af, 0x3fdf38c567bcc541, 0x3fdf59ab4286576c,
    0x3fdf7a8568cb06cf, 0x3fdf9b53e2dc34c4, 0x3fdfbc16b902680a, 0x3fdfdccdf37d594c,
    0x3fdffd799a83ff9b, 0x3fe00f0cdb224e65, 0x3fe01f57277264e0, 0x3fe02f9bb640c151,
    0x3fe03fda8b97997f, 0x3fe05013ab7ce0e6, 0x3fe0604719f24eb2, 0x3fe07074daf563b3,
    0x3fe0809cf27f703d, 0x3fe090bf64859a08, 0x3fe0a0dc34f8e1fc, 0x3fe0b0f367c629fd,
    0x3fe0c10500d63aa6, 0x3fe0d111040dc8fb, 0x3fe0e117754d7c11, 0x3fe0f1185871f2b1,
    0x3fe10113b153c8ea, 0x3fe1110983c79d9f, 0x3fe120f9d39e1807, 0x3fe130e4a4a3ed28,
    0x3fe140c9faa1e544, 0x3fe150a9d95ce141, 0x3fe160844495e006, 0x3fe17059400a03cc,
    0x3fe18028cf72976a, 0x3fe18ff2f6851397, 0x3fe19fb7b8f32421, 0x3fe1af771a6aad1d,
    0x3fe1bf311e95d00e, 0x3fe1cee5c91af101, 0x3fe1de951d9cbba6, 0x3fe1ee3f1fba2859,
    0x3fe1fde3d30e8126, 0x3fe20d833b3166c9, 0x3fe21d1d5bb6d59a, 0x3fe22cb2382f2a7f,
    0x3fe23c41d42727c8, 0x3fe24bcc3327fa0f, 0x3fe25b5158b73d04, 0x3fe26ad14857003f,
    0x3fe27a4c0585cbf8, 0x3fe289c193bea5ca, 0x3fe29931f6791560, 0x3fe2a89d31292921,
    0x3fe2b803473f7ad1, 0x3fe2c7643c29342e, 0x3fe2d6c013501380, 0x3fe2e616d01a702a,
    0x3fe2f56875eb3f26, 0x3fe304b508221789, 0x3fe313fc8a1b36f2, 0x3fe3233eff2f85fe,
    0x3fe3327c6ab49ca7, 0x3fe341b4cffcc6a9, 0x3fe350e8325707d9, 0x3fe36016950f2072,
    0x3fe36f3ffb6d9162, 0x3fe37e6468b7a08e, 0x3fe38d83e02f5d09, 0x3fe39c9e6513a34d,
    0x3fe3abb3faa02167, 0x3fe3bac4a40d5b1d, 0x3fe3c9d06490ae12, 0x3fe3d8d73f5c55dc,
    0x3fe3e7d9379f7016, 0x3fe3f6d650860073, 0x3fe405ce8d38f4bc, 0x3fe414c1f0de28d2,
    0x3fe423b07e986aa9, 0x3fe4329a39877e38, 0x3fe4417f24c82165, 0x3fe4505f43740fea,
    0x3fe45f3a98a20739, 0x3fe46e112765ca4d, 0x3fe47ce2f2d02587, 0x3fe48baffdeef271,
    0x3fe49a784bcd1b8b, 0x3fe4a93bdf72a00b, 0x3fe4b7fabbe49795, 0x3fe4c6b4e42535f4,
    0x3fe4d56a5b33cec4, 0x3fe4e41b240cd91f, 0x3fe4f2c741a9f33e, 0x3fe5016eb701e619,
    0x3fe510118708a8f9, 0x3fe51eafb4af6512, 0x3fe52d4942e47909, 0x3fe53bde34937c7f,
    0x3fe54a6e8ca5438e, 0x3fe558fa4dffe248, 0x3fe567817b86b02c, 0x3fe57604181a4b99,
    0x3fe5848226989d34, 0x3fe592fba9dcdb53, 0x3fe5a170a4bf8d5c, 0x3fe5afe11a168f21,
    0x3fe5be4d0cb51435, 0x3fe5ccb47f6bab3c, 0x3fe5db177508413c, 0x3fe5e975f05624dd,
    0x3fe5f7cff41e09af, 0x3fe6062583260b63, 0x3fe61476a031b109, 0x3fe622c34e01f039,
    0x3fe6310b8f553048, 0x3fe63f4f66e74d70, 0x3fe64d8ed7719bf0, 0x3fe65bc9e3aaeb2c,
    0x3fe66a008e4788cc, 0x3fe67832d9f943ca, 0x3fe68660c96f6f87, 0x3fe6948a5f56e6d8,
    0x3fe6a2af9e5a0f0a, 0x3fe6b0d08920dae6, 0x3fe6beed2250cdae, 0x3fe6cd056c8cfe1a,
    0x3fe6db196a76194a, 0x3fe6e9291eaa65b5, 0x3fe6f7348bc5c618, 0x3fe7053bb461bc5c,
    0x3fe7133e9b156c7c, 0x3fe7213d42759f5d, 0x3fe72f37ad14c5b0, 0x3fe73d2ddd82fac2,
    0x3fe74b1fd64e0754, 0x3fe7590d9a016461, 0x3fe766f72b263dee, 0x3fe774dc8c4375cb,
    0x3fe782bdbfdda657, 0x3fe7909ac877253b, 0x3fe79e73a8900620, 0x3fe7ac4862a61d6a,
    0x3fe7ba18f93502e4, 0x3fe7c7e56eb6146e, 0x3fe7d5adc5a078a4, 0x3fe7e37200692186,
    0x3fe7f1322182cf16, 0x3fe7feee2b5e11f4, 0x3fe80ca620694df9, 0x3fe81a5a0310bccc,
    0x3fe82809d5be7073, 0x3fe835b59ada55de, 0x3fe8435d54ca3774, 0x3fe8510105f1bf97,
    0x3fe85ea0b0b27b26, 0x3fe86c3c576bdbfe, 0x3fe879d3fc7b3b71, 0x3fe88767a23bdcbf,
    0x3fe894f74b06ef8b, 0x3fe8a282f9339249, 0x3fe8b00aaf16d4a9, 0x3fe8bd8e6f03ba04,
    0x3fe8cb0e3b4b3bbe, 0x3fe8d88a163c4ba8, 0x3fe8e6020223d661, 0x3fe8f376014cc5ac,
    0x3fe900e6160002cd, 0x3fe90e52428478d9, 0x3fe91bba891f1709, 0x3fe9291eec12d304,
    0x3fe9367f6da0ab2f, 0x3fe943dc1007a8ec, 0x3fe95134d584e2e3, 0x3fe95e89c0537f42,
    0x3fe96bdad2acb5f6, 0x3fe979280ec7d2e7, 0x3fe9867176da382f, 0x3fe993b70d17604b,
    0x3fe9a0f8d3b0e050, 0x3fe9ae36ccd66a10, 0x3fe9bb70fab5ce4d, 0x3fe9c8a75f7afed6,
    0x3fe9d5d9fd5010b3, 0x3fe9e308d65d3e43, 0x3fe9f033ecc8e956, 0x3fe9fd5b42b79d4d,
    0x3fea0a7eda4c112d, 0x3fea179eb5a729b7, 0x3fea24bad6e7fb77, 0x3fea31d3402bccd5,
    0x3fea3ee7f38e181f, 0x3fea4bf8f3288d93, 0x3fea590641131564, 0x3fea660fdf63d1bf,
    0x3fea7315d02f20c8, 0x3fea801815879e9b, 0x3fea8d16b17e2745, 0x3fea9a11a621d8bc,
    0x3feaa708f58014d3, 0x3feab3fca1a48332, 0x3feac0ecac99133b, 0x3feacdd91865fe03,
    0x3feadac1e711c833, 0x3feae7a71aa143f5, 0x3feaf488b51792d6, 0x3feb0166b87627aa,
    0x3feb0e4126bcc86c, 0x3feb1b1801e99018, 0x3feb27eb4bf8f08a, 0x3feb34bb06e5b452,
    0x3feb418734a9008c, 0x3feb4e4fd73a56b0, 0x3feb5b14f08f9666, 0x3feb67d6829cff51,
    0x3feb74948f5532da, 0x3feb814f18a935fd, 0x3feb8e0620887309, 0x3feb9ab9a8e0bb69,
    0x3feba769b39e4964, 0x3febb41642abc1db, 0x3febc0bf57f23606, 0x3febcd64f5592530,
    0x3febda071cc67e6e, 0x3febe6a5d01ea253, 0x3febf341114464a7, 0x3febffd8e2190e13,
    0x3fec0c6d447c5dd3, 0x3fec18fe3a4c8b64, 0x3fec258bc5664829, 0x3fec3215e7a4c116,
    0x3fec3e9ca2e1a055, 0x3fec4b1ff8f50eec, 0x3fec579febb5b658, 0x3fec641c7cf8c232,
    0x3fec7095ae91e1c7, 0x3fec7d0b825349b9, 0x3fec897dfa0db58e, 0x3fec95ed1790694e,
    0x3feca258dca93316, 0x3fecaec14b246ca7, 0x3fecbb2664ccfcf6, 0x3fecc7882b6c59be,
    0x3fecd3e6a0ca8907, 0x3fece041c6ae22b3, 0x3fecec999edc5203, 0x3fecf8ee2b18d71f,
    0x3fed053f6d260896, 0x3fed118d66c4d4e5, 0x3fed1dd819b4c3f1, 0x3fed2a1f87b3f886,
    0x3fed3663b27f31d5, 0x3fed42a49bd1ccec, 0x3fed4ee24565c62b, 0x3fed5b1cb0f3babe,
    0x3fed6753e032ea0f, 0x3fed7387d4d93736, 0x3fed7fb8909b2a6c, 0x3fed8be6152bf277,
    0x3fed9810643d6615, 0x3feda4377f80056a, 0x3fedb05b68a2fb65, 0x3fedbc7c21541f28,
    0x3fedc899ab3ff56c, 0x3fedd4b40811b1e6, 0x3fede0cb397338a4, 0x3fedecdf410d1f71,
    0x3fedf8f02086af2c, 0x3fee04fdd985e52d, 0x3fee11086daf7496, 0x3fee1d0fdea6c7b0,
    0x3fee29142e0e0140, 0x3fee35155d85fddc, 0x3fee41136eae553d, 0x3fee4d0e63255b92,
    0x3fee59063c8822ce, 0x3fee64fafc727bf7, 0x3fee70eca47ef86f, 0x3fee7cdb3646eb44,
    0x3fee88c6b3626a73, 0x3fee94af1d685033, 0x3feea09475ee3c3a, 0x3feeac76be8894fe,
    0x3feeb855f8ca88fb, 0x3feec43226460ff1, 0x3feed00b488bec23, 0x3feedbe1612bab98,
    0x3feee7b471b3a950, 0x3feef3847bb10e87, 0x3feeff5180afd3e4, 0x3fef0b1b823ac2b8,
    0x3fef16e281db7630, 0x3fef22a6811a5c8a, 0x3fef2e67817eb845, 0x3fef3a25848ea156,
    0x3fef45e08bcf0655, 0x3fef519898c3adab, 0x3fef5d4dacef36be, 0x3fef68ffc9d31b1f,
    0x3fef74aef0efafae, 0x3fef805b23c425c8, 0x3fef8c0463ce8c69, 0x3fef97aab28bd153,
    0x3fefa34e1177c233, 0x3fefaeee820d0dc1, 0x3fefba8c05c544df, 0x3fefc6269e18dbbf,
    0x3fefd1be4c7f2af9, 0x3fefdd53126e70ae, 0x3fefe8e4f15bd1a0, 0x3feff473eabb5a4b,
];
/// 2^(j/128), correctly rounded (bits), j = 0…127.
#[rustfmt::skip]
const EXP2_FRACTION: [u64; 128] = [
    0x3ff0000000000000, 0x3ff0163da9fb3335, 0x3ff02c9a3e778061, 0x3ff04315e86e7f85,
    0x3ff059b0d3158574, 0x3ff0706b29ddf6de, 0x3ff0874518759bc8, 0x3ff09e3ecac6f383,
    0x3ff0b5586cf9890f, 0x3ff0cc922b7247f7, 0x3ff0e3ec32d3d1a2, 0x3ff0fb66affed31b,
    0x3ff11301d0125b51, 0x3ff12abdc06c31cc, 0x3ff1429aaea92de0, 0x3ff15a98c8a58e51,
    0x3ff172b83c7d517b, 0x3ff18af9388c8dea, 0x3ff1a35beb6fcb75, 0x3ff1bbe084045cd4,
    0x3ff1d4873168b9aa, 0x3ff1ed5022fcd91d, 0x3ff2063b88628cd6, 0x3ff21f49917ddc96,
    0x3ff2387a6e756238, 0x3ff251ce4fb2a63f, 0x3ff26b4565e27cdd, 0x3ff284dfe1f56381,
    0x3ff29e9df51fdee1, 0x3ff2b87fd0dad990, 0x3ff2d285a6e4030b, 0x3ff2ecafa93e2f56,
    0x3ff306fe0a31b715, 0x3ff32170fc4cd831, 0x3ff33c08b26416ff, 0x3ff356c55f929ff1,
    0x3ff371a7373aa9cb, 0x3ff38cae6d05d866, 0x3ff3a7db34e59ff7, 0x3ff3c32dc313a8e5,
    0x3ff3dea64c123422, 0x3ff3fa4504ac801c, 0x3ff4160a21f72e2a, 0x3ff431f5d950a897,
    0x3ff44e086061892d, 0x3ff46a41ed1d0057, 0x3ff486a2b5c13cd0, 0x3ff4a32af0d7d3de,
    0x3ff4bfdad5362a27, 0x3ff4dcb299fddd0d, 0x3ff4f9b2769d2ca7, 0x3ff516daa2cf6642,
    0x3ff5342b569d4f82, 0x3ff551a4ca5d920f, 0x3ff56f4736b527da, 0x3ff58d12d497c7fd,
    0x3ff5ab07dd485429, 0x3ff5c9268a5946b7, 0x3ff5e76f15ad2148, 0x3ff605e1b976dc09,
    0x3ff6247eb03a5585, 0x3ff6434634ccc320, 0x3ff6623882552225, 0x3ff68155d44ca973,
    0x3ff6a09e667f3bcd, 0x3ff6c012750bdabf, 0x3ff6dfb23c651a2f, 0x3ff6ff7df9519484,
    0x3ff71f75e8ec5f74, 0x3ff73f9a48a58174, 0x3ff75feb564267c9, 0x3ff780694fde5d3f,
    0x3ff7a11473eb0187, 0x3ff7c1ed0130c132, 0x3ff7e2f336cf4e62, 0x3ff80427543e1a12,
    0x3ff82589994cce13, 0x3ff8471a4623c7ad, 0x3ff868d99b4492ed, 0x3ff88ac7d98a6699,
    0x3ff8ace5422aa0db, 0x3ff8cf3216b5448c, 0x3ff8f1ae99157736, 0x3ff9145b0b91ffc6,
    0x3ff93737b0cdc5e5, 0x3ff95a44cbc8520f, 0x3ff97d829fde4e50, 0x3ff9a0f170ca07ba,
    0x3ff9c49182a3f090, 0x3ff9e86319e32323, 0x3ffa0c667b5de565, 0x3ffa309bec4a2d33,
    0x3ffa5503b23e255d, 0x3ffa799e1330b358, 0x3ffa9e6b5579fdbf, 0x3ffac36bbfd3f37a,
    0x3ffae89f995ad3ad, 0x3ffb0e07298db666, 0x3ffb33a2b84f15fb, 0x3ffb59728de5593a,
    0x3ffb7f76f2fb5e47, 0x3ffba5b030a1064a, 0x3ffbcc1e904bc1d2, 0x3ffbf2c25bd71e09,
    0x3ffc199bdd85529c, 0x3ffc40ab5fffd07a, 0x3ffc67f12e57d14b, 0x3ffc8f6d9406e7b5,
    0x3ffcb720dcef9069, 0x3ffcdf0b555dc3fa, 0x3ffd072d4a07897c, 0x3ffd2f87080d89f2,
    0x3ffd5818dcfba487, 0x3ffd80e316c98398, 0x3ffda9e603db3285, 0x3ffdd321f301b460,
    0x3ffdfc97337b9b5f, 0x3ffe264614f5a129, 0x3ffe502ee78b3ff6, 0x3ffe7a51fbc74c83,
    0x3ffea4afa2a490da, 0x3ffecf482d8e67f1, 0x3ffefa1bee615a27, 0x3fff252b376bba97,
    0x3fff50765b6e4540, 0x3fff7bfdad9cbe14, 0x3fffa7c1819e90d8, 0x3fffd3c22b8f71f1,
];

/// 1/(1 + j/512), each one correctly rounded division (IEEE arithmetic when compiling: the same bits on
/// every platform).
const INV_CELL: [f64; 512] = {
    let mut t = [0.0; 512];
    let mut j = 0;
    while j < 512 {
        t[j] = 1.0 / (1.0 + j as f64 / 512.0);
        j += 1;
    }
    t
};

/// (−1)^(i+1)/(i ln 2), i = 1…5: log₂(1 + r) = Σ L_i rⁱ (`scripts/pow_tables.py`).
#[allow(clippy::excessive_precision)]
const LOG2_1P: [f64; 5] = [
    std::f64::consts::LOG2_E, // 1/ln 2, correctly rounded as the table's generator gives it
    -0.721_347_520_444_481_7,
    0.480_898_346_962_987_8,
    -0.360_673_760_222_240_85,
    0.288_539_008_177_792_66,
];

/// (ln 2/128)^i/i!, i = 1…5: 2^(σ/128) − 1 = Σ E_i σⁱ for σ = 128 s ∈ [−½, ½] (`scripts/pow_tables.py`).
#[allow(clippy::excessive_precision)]
const EXP2_S128: [f64; 5] = [
    5.415_212_348_124_572_5e-3,
    1.466_226_238_764_042_5e-5,
    2.646_642_144_433_097e-8,
    3.583_032_305_400_251e-11,
    3.880_576_156_786_539e-14,
];

/// 1.5·2⁵² (see [`vmath`](super::vmath)): adding it rounds to an integer held in the low fraction bits.
const SHIFT: f64 = super::vmath::SHIFT;

/// 2^k for −1022 ≤ k ≤ 1023, exactly, from the exponent bits.
#[inline(always)]
fn pow2i(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// x^p for a positive normal x and a finite p (see the module docs for the formula and the accuracy), and
/// ∞^p as `powf` gives it; NaN where x or p is NaN and for x outside its domain (zero, subnormal, negative),
/// never a wrong finite number.
///
/// # Examples
/// ```
/// use stochvib::linalg::vpow::pow_positive;
/// assert_eq!(pow_positive(1.0, -2.7), 1.0);
/// assert_eq!(pow_positive(2.0, 10.0), 1024.0);
/// // within (1.5 + 0.5·2 + 2·6.7)ε of 0.01 (POW_ERROR, t = −2 log₂ 10)
/// assert!((pow_positive(10.0, -2.0) - 0.01).abs() <= 16.0 * f64::EPSILON * 0.01);
/// assert!(pow_positive(f64::NAN, 2.0).is_nan());
/// ```
#[inline(always)]
pub fn pow_positive(x: f64, p: f64) -> f64 {
    // p·(128u): the bits of (128p)·u, without 128p overflowing for |p| > 10³⁰⁶
    let y = exp2_128::<true>(p * (128.0 * log2(x, 0.0)));
    if x.is_nan() || p.is_nan() || x < f64::MIN_POSITIVE {
        f64::NAN
    } else if x == f64::INFINITY {
        // ∞^p: ∞ for p > 0, 0 for p < 0, 1 for p = 0
        if p > 0.0 {
            x
        } else if p < 0.0 {
            0.0
        } else {
            1.0
        }
    } else {
        y
    }
}

/// The power law x ↦ (x/x₀)^p from a base point x₀, prepared once for many x (a segment of a tabulated
/// density): the ratio by a multiplication with 1/x₀ instead of a division, its rounding of 1/x₀ taken out
/// of the logarithm, and exactly 1 at x = x₀.
///
/// # Formula
/// With r₀ = fl(1/x₀) = (1 + δ)/x₀ (δ = x₀r₀ − 1, exact by one fused multiply-add when prepared),
/// log₂(x/x₀) = log₂(fl(x·r₀)) − log₂(1 + δ) − log₂(1 + ρ) for the product's rounding |ρ| ≤ ε/2, the same
/// error as a correctly rounded x/x₀; log₂(1 + δ) = δ/ln 2 to within δ²/2 < 10⁻³². So (x/x₀)^p is within
/// [`POW_ERROR`] of the exact power of the rounded ratio, and ρ adds |p|ε/2: relative to the exact
/// (x/x₀)^p, (c₀ + (c_p + ½)|p| + c_t|t|)·ε.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PowerFrom {
    base: f64,
    inv: f64,
    lead: f64,
    p128: f64,
}

impl PowerFrom {
    /// The law (x/`base`)^`p` on x ∈ [`base`, `top`] without a clamp of the exponent: None unless `base`
    /// and 1/`base` are normal, `top`/`base` finite, `p` finite and |p log₂(top/base)| ≤ 1000. Then
    /// (x/x₀)^p lies within 2^±1000, a normal number: a factor multiplying it over- or underflows only where
    /// the product itself does (and [`at`](Self::at), whose range is |t| ≤ 2000, needs no clamp). None only
    /// for absurd laws: a ratio (top/x₀)^|p| beyond 2¹⁰⁰⁰ (a density changing by 10³⁰¹ between two nodes),
    /// or a base or 1/base outside the normal range (a base below 2⁻¹⁰²² ≈ 2.2·10⁻³⁰⁸ or above
    /// 2¹⁰²² ≈ 4.5·10³⁰⁷).
    pub(crate) fn up_to(base: f64, p: f64, top: f64) -> Option<PowerFrom> {
        let inv = 1.0 / base;
        let ratio = top * inv;
        let fits = base.is_normal()
            && inv.is_normal()
            && ratio.is_normal()
            && base > 0.0
            && top >= base
            && p.is_finite()
            // the exponent reached, with the rounding of log₂ (≤ (0.6 + 2|u|)ε < 10⁻¹² for |u| < 2100) and of
            // `lead` included: a p near 10¹⁹ (nodes a few ulp apart) must not carry it past the bound
            && p.abs() * (ratio.log2().abs() + 1e-12) <= 1000.0;
        fits.then(|| PowerFrom {
            base,
            inv,
            lead: base.mul_add(inv, -1.0) * std::f64::consts::LOG2_E,
            p128: 128.0 * p,
        })
    }

    /// (x/x₀)^p for x ∈ [x₀, top] of [`up_to`](Self::up_to) (other x: meaningless).
    #[inline(always)]
    pub(crate) fn at(&self, x: f64) -> f64 {
        let y = exp2_128::<false>(self.p128 * log2(x * self.inv, self.lead));
        if x == self.base {
            1.0
        } else {
            y
        }
    }
}

/// log₂ x − `lead` for a positive normal finite x (see the module docs; `lead` a correction below 10⁻¹⁵,
/// subtracted from the exponent before the sums).
#[inline(always)]
fn log2(x: f64, lead: f64) -> f64 {
    let b = x.to_bits();
    let j = ((b & CELL) >> 43) as usize;
    let m = f64::from_bits((b & FRACTION) | ONE);
    let c = f64::from_bits((b & CELL) | ONE);
    let r = (m - c) * INV_CELL[j];
    let r2 = r * r;
    let [l1, l2, l3, l4, l5] = LOG2_1P;
    let log1p = r * ((l1 + r * l2) + r2 * ((l3 + r * l4) + r2 * l5));
    // the exponent field k + 1023 ≤ 2047 in the low bits of SHIFT's fraction: k exactly, no integer
    // conversion (none that SSE2 and AVX2 vectorise)
    let k = f64::from_bits(SHIFT.to_bits() | (b >> 52)) - (SHIFT + 1023.0);
    ((k - lead) + f64::from_bits(LOG2_CELL[j])) + log1p
}

/// 2^(τ/128) for τ = 128 t (the second half of the power). With `CLAMPED`, τ is first clamped to
/// 128·[−1080, 1025], which makes a result beyond the range 0 or +∞; without, τ must lie within
/// 128·[−2000, 2000]: then e = ⌊n/128⌋ ∈ [−2000, 2000] splits into two exact powers of two of at most
/// 2^±1000 each (a result beyond the range is still 0 or +∞, rounded once) and the logical shifts below see
/// positive numbers.
#[inline(always)]
fn exp2_128<const CLAMPED: bool>(tau: f64) -> f64 {
    let tau = if CLAMPED {
        tau.clamp(-1080.0 * 128.0, 1025.0 * 128.0)
    } else {
        tau
    };
    let nd = tau + SHIFT;
    // n = round(τ) as the difference of the bits (two's complement for n < 0)
    let n = nd.to_bits().wrapping_sub(SHIFT.to_bits());
    // σ = τ − n ∈ [−½, ½], exact (τ and n within a factor 2 of each other, or n = 0)
    let sigma = tau - (nd - SHIFT);
    let i = (n & 127) as usize;
    // e = ⌊n/128⌋ and its halves by logical shifts of positive numbers (no 64-bit arithmetic shift on SSE2
    // and AVX2)
    let e = ((n.wrapping_add(2048 << 7)) >> 7) as i64 - 2048;
    let e1 = ((e + 2048) as u64 >> 1) as i64 - 1024;
    let s2 = sigma * sigma;
    let [c1, c2, c3, c4, c5] = EXP2_S128;
    let q = sigma * ((c1 + sigma * c2) + s2 * ((c3 + sigma * c4) + s2 * c5));
    let f = f64::from_bits(EXP2_FRACTION[i]);
    (f + f * q) * pow2i(e1) * pow2i(e - e1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::vmath::{map_on, Isa, Kernel};

    /// A xorshift stream of uniforms in [0, 1) (the tests' arguments; any fixed sequence will do).
    fn uniforms(mut x: u64) -> impl FnMut() -> f64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// (x, p) pairs: x log-uniform over 10⁻³⁰⁰…10³⁰⁰ and over the segments of tables (1…10⁴, and within
    /// 10⁻⁶ above 1, where log₂ x → 0), cell edges j/512 at random binades and their neighbours; p uniform in [−12, 12],
    /// integers and small |p|; kept where x^p is normal and at least 4 binades inside the range.
    fn arguments() -> Vec<(f64, f64)> {
        let mut u = uniforms(0x2545_F491_4F6C_DD1D);
        let mut v = Vec::new();
        for i in 0..1_000_000 {
            let x = match i % 4 {
                0 => 10f64.powf(-300.0 + 600.0 * u()),
                1 => 10f64.powf(4.0 * u()),
                2 => 1.0 + 1e-6 * u(),
                _ => {
                    let edge = 2f64.powi((u() * 40.0) as i32 - 20) * (1.0 + (u() * 256.0).floor() / 256.0);
                    f64::from_bits((edge.to_bits() as i64 + (u() * 5.0) as i64 - 2) as u64)
                }
            };
            let p = match i % 3 {
                0 => -12.0 + 24.0 * u(),
                1 => (-12.0 + 24.0 * u()).round(),
                _ => 1e-3 * (u() - 0.5),
            };
            let t = p * x.log2();
            if t.abs() < 1018.0 {
                v.push((x, p));
            }
        }
        v
    }

    /// [`pow_positive`] against libm's `powf` (glibc's pow: < 1 ulp) over [`arguments`] (those of 10⁶ draws
    /// whose power is normal): within [`POW_ERROR`]
    /// of the module docs plus the oracle's own ulp (ε), relative. The largest share of the allowed error it
    /// reaches is printed (`--nocapture`).
    #[test]
    fn within_the_stated_error_of_libm() {
        let (c0, cp, ct) = POW_ERROR;
        let mut worst = (0.0f64, 0.0, 0.0);
        for (x, p) in arguments() {
            let (a, b) = (pow_positive(x, p), x.powf(p));
            let t = p * x.log2();
            let allowed = (c0 + 1.0 + cp * p.abs() + ct * t.abs()) * f64::EPSILON;
            let err = (a - b).abs() / b;
            assert!(
                err <= allowed,
                "pow_positive({x:e}, {p}) = {a:e}, libm {b:e}: {err:e} > {allowed:e}"
            );
            if err / allowed > worst.0 {
                worst = (err / allowed, x, p);
            }
        }
        eprintln!(
            "worst: {:.3} of the allowed at x = {:e}, p = {}",
            worst.0, worst.1, worst.2
        );
    }

    /// [`PowerFrom`] against libm's `powf` of the exact ratio: bases of 26 significant bits over
    /// 10⁻¹⁰⁰…10¹⁰⁰ and ratios x of 26 bits (those of [`arguments`] in [1, 10⁴⁰) with |p log₂ x| ≤ 999, the
    /// range [`PowerFrom::up_to`] takes), so that
    /// w = base·x and w/base = x are exact. Within its bound of the exact power, [`POW_ERROR`] with c_p + ½
    /// (the rounding of w·fl(1/base)), plus the oracle's own ulp (ε); exactly 1 at the base.
    #[test]
    fn a_prepared_law_is_within_its_error_of_libm() {
        let (c0, cp, ct) = POW_ERROR;
        let mut u = uniforms(0x9E37_79B9_7F4A_7C15);
        let bits26 = |v: f64| f64::from_bits(v.to_bits() & !((1u64 << 27) - 1));
        let mut worst = 0.0f64;
        let within = |&(x, p): &(f64, f64)| (1.0..1e40).contains(&x) && (p * x.log2()).abs() <= 999.0;
        for (x, p) in arguments().into_iter().filter(within) {
            let (base, x) = (bits26(10f64.powf(-100.0 + 200.0 * u())), bits26(x));
            let w = base * x;
            assert_eq!(w / base, x, "an exact ratio");
            let Some(law) = PowerFrom::up_to(base, p, w) else {
                panic!("declined: base {base:e}, p {p}, top {w:e}");
            };
            assert_eq!(law.at(base), 1.0, "base {base:e}, p {p}");
            let (a, b) = (law.at(w), x.powf(p));
            let t = p * x.log2();
            let allowed = (c0 + 1.0 + (cp + 0.5) * p.abs() + ct * t.abs()) * f64::EPSILON;
            let err = (a - b).abs() / b;
            assert!(
                err <= allowed,
                "({w:e}/{base:e})^{p} = {a:e}, libm {b:e}: {err:e} > {allowed:e}"
            );
            worst = worst.max(err / allowed);
        }
        eprintln!("worst: {worst:.3} of the allowed");
    }

    /// [`PowerFrom::up_to`] declines what its unclamped formula cannot take: a subnormal or huge base,
    /// a non-finite p, and a ratio to the power p beyond 2¹⁰⁰⁰; it takes 2⁹⁹⁹, and there the unclamped
    /// result is the clamped one's bits.
    #[test]
    fn a_prepared_law_declines_what_it_cannot_take() {
        assert!(PowerFrom::up_to(1e-310, 1.0, 1.0).is_none());
        assert!(PowerFrom::up_to(1e308, 1.0, 1.5e308).is_none()); // 1/base subnormal
        assert!(PowerFrom::up_to(1.0, f64::NAN, 2.0).is_none());
        assert!(PowerFrom::up_to(1.0, f64::INFINITY, 2.0).is_none());
        assert!(PowerFrom::up_to(1.0, 1001.0, 2.0).is_none());
        assert!(PowerFrom::up_to(1.0, -1001.0, 2.0).is_none());
        for p in [999.0, -999.0] {
            let law = PowerFrom::up_to(1.0, p, 2.0).expect("within the range");
            for x in [1.0, 1.3, 1.7, 2.0] {
                assert_eq!(law.at(x).to_bits(), pow_positive(x, p).to_bits(), "{x}^{p}");
            }
        }
    }

    /// The literal tables (from `scripts/pow_tables.py`) against libm: every log₂(1 + j/512) and 2^(j/128)
    /// the bits of glibc's `log2`/`exp2`, which are correctly rounded at all 640 of these arguments (a
    /// libm that is not would show here first; a wrong or shifted entry fails), and the edges exact:
    /// log₂ 1 = 0, 2⁰ = 1.
    #[test]
    fn the_tables_are_the_values_they_name() {
        let ulps = |a: f64, b: f64| (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs();
        assert_eq!(LOG2_CELL[0], 0);
        assert_eq!(f64::from_bits(EXP2_FRACTION[0]), 1.0);
        for (j, bits) in LOG2_CELL.iter().enumerate().skip(1) {
            let want = (1.0 + j as f64 / 512.0).log2();
            assert_eq!(ulps(f64::from_bits(*bits), want), 0, "log2 cell {j}");
        }
        for (j, bits) in EXP2_FRACTION.iter().enumerate() {
            assert_eq!(ulps(f64::from_bits(*bits), (j as f64 / 128.0).exp2()), 0, "2^({j}/128)");
        }
        assert_eq!(LOG2_1P[0], std::f64::consts::LOG2_E);
        assert_eq!(EXP2_S128[0], std::f64::consts::LN_2 / 128.0);
    }

    /// x = 1 gives 1 exactly for every p (the nodes of a tabulated density reproduce the table); p = 0 gives
    /// 1; powers of two to integer powers are exact; beyond the range the result is 0 or +∞; NaN stays NaN.
    #[test]
    fn exact_values_and_the_range() {
        let mut u = uniforms(7);
        for _ in 0..10_000 {
            let p = -50.0 + 100.0 * u();
            assert_eq!(pow_positive(1.0, p), 1.0, "p = {p}");
            let x = 10f64.powf(-300.0 + 600.0 * u());
            assert_eq!(pow_positive(x, 0.0), 1.0, "x = {x:e}");
        }
        for k in -30..=30 {
            for p in -30..=30 {
                let want = 2f64.powi(k * p);
                if want.is_normal() {
                    assert_eq!(pow_positive(2f64.powi(k), f64::from(p)), want, "2^{k} to the {p}");
                }
            }
        }
        assert_eq!(pow_positive(10.0, 400.0), f64::INFINITY);
        assert_eq!(pow_positive(1e300, 2.0), f64::INFINITY);
        assert_eq!(pow_positive(10.0, -400.0), 0.0);
        assert_eq!(pow_positive(1e-300, 2.0), 0.0);
        // a subnormal result, rounded once: 2^(−1060) exactly
        assert_eq!(pow_positive(2f64.powi(-53), 20.0), f64::from_bits(1 << 14));
        assert!(pow_positive(f64::NAN, 2.0).is_nan() && pow_positive(2.0, f64::NAN).is_nan());
        // ∞^p as powf, and a huge p at x = 1 (128p would overflow)
        assert_eq!(pow_positive(f64::INFINITY, 2.0), f64::INFINITY);
        assert_eq!(pow_positive(f64::INFINITY, -2.0), 0.0);
        assert_eq!(pow_positive(f64::INFINITY, 0.0), 1.0);
        assert_eq!(pow_positive(1.0, 1e307), 1.0);
        assert_eq!(pow_positive(1.0, -1e307), 1.0);
        // outside the domain: NaN, not a number from the bits of a zero, subnormal or negative x
        for x in [0.0, -0.0, 5e-324, 1e-310, -2.0, f64::NEG_INFINITY] {
            assert!(pow_positive(x, 1.5).is_nan(), "x = {x:e}");
        }
    }

    /// Every instruction set the CPU has (AVX-512, AVX2 and the baseline forced in turn) gives the bits of
    /// the scalar formula, table reads by gathers or lane by lane included, also on the slice tails that
    /// the vector loops leave to scalar code (lengths 0..=19).
    #[test]
    fn every_isa_gives_the_bits_of_the_scalar_formula() {
        // kernels as types, so that `map_on` compiles the formula into its vector loops (gathers on
        // AVX-512); a `dyn Fn` or a function pointer would stay an indirect call there, and the loops scalar
        #[derive(Clone, Copy)]
        struct Pow(f64);
        impl Kernel for Pow {
            #[inline(always)]
            fn at(&self, x: f64) -> f64 {
                pow_positive(x, self.0)
            }
        }
        #[derive(Clone, Copy)]
        struct Law(PowerFrom);
        impl Kernel for Law {
            #[inline(always)]
            fn at(&self, x: f64) -> f64 {
                self.0.at(x)
            }
        }
        fn check<K: Kernel + Copy>(k: K, x: &[f64], what: &str) {
            let want: Vec<u64> = x.iter().map(|&v| k.at(v).to_bits()).collect();
            for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
                for len in (0..=19).chain([x.len()]) {
                    let mut out = vec![0.0; len];
                    map_on(isa, &x[..len], &mut out, k);
                    let got: Vec<u64> = out.iter().map(|v| v.to_bits()).collect();
                    assert_eq!(got, want[..len], "{what}: {isa:?}, length {len}");
                }
            }
        }
        let x: Vec<f64> = arguments().iter().map(|a| a.0).collect();
        let ratios: Vec<f64> = x.iter().filter(|x| **x >= 1.0 && **x < 1e25).map(|x| 3.7 * x).collect();
        for p in [-3.7, -1.0, 0.25, 2.0, 11.5] {
            check(Pow(p), &x, &format!("pow_positive, p = {p}"));
            let law = PowerFrom::up_to(3.7, p, 3.7e25).expect("a law in range");
            check(Law(law), &ratios, &format!("PowerFrom, p = {p}"));
        }
    }
}
