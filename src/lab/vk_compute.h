/* vk_compute.h — one compute pipeline on a Vulkan device for the shader
 * kernel convention (vk_compute.c; docs/check-your-kernel.md, "Shaders").
 * Not installed.  Built without Vulkan, every call is SH_ENOTSUP. */
#ifndef SHLAB_VK_COMPUTE_H
#define SHLAB_VK_COMPUTE_H

#include <stddef.h>
#include <stdint.h>

/* The convention's workgroup width: a shader declares local_size_x = 64. */
#define SH_VK_LOCAL_SIZE 64

typedef struct sh_vk sh_vk;
/* 1 if shlab was built with Vulkan. */
int sh_vk_available(void);
/* Instance and device: device ≥ 0 its index, −1 the first GPU (else the
 * first device: lavapipe on a machine without a GPU). */
int sh_vk_open(int device, sh_vk **out);
const char *sh_vk_device_name(const sh_vk *v);
const char *sh_vk_driver(const sh_vk *v);
int sh_vk_is_cpu(const sh_vk *v);
/* The compute pipeline of the SPIR-V's entry point, with the convention's
 * layout (set 0: four storage buffers; 16 bytes of push constants). */
int sh_vk_pipeline(sh_vk *v, const uint32_t *spirv, size_t nwords, const char *entry);
/* The four buffers (bytes each; host-visible, mapped into map[]). */
int sh_vk_buffers(sh_vk *v, const size_t bytes[4], void *map[4]);
/* Record `repeat` dispatches of count rotations of the order (push
 * constants order, count, form), then submit and wait up to timeout_s.
 * count 0 dispatches one group that does nothing: a driver that compiles
 * the shader at its first dispatch (lavapipe) does it then. */
int sh_vk_record(sh_vk *v, int order, int count, int form, int repeat);
int sh_vk_submit(sh_vk *v, double timeout_s);
void sh_vk_close(sh_vk *v);

#endif
