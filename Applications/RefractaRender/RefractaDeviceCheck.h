// refracta-render --device-check: the OpenCL end-to-end check of earlier versions.
#ifndef RefractaDeviceCheck_h
#define RefractaDeviceCheck_h

namespace RefractaRender
{
/// Builds the atomics kernels on the default device and sums 2^20 values with fixed-point
/// atomics under full contention; true (and "device check passed") when the sum is exact.
bool DeviceCheck();
}

#endif
