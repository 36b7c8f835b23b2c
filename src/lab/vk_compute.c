/* vk_compute.c — one compute pipeline on a Vulkan device: the shader
 * kernel convention of docs/check-your-kernel.md ("Shaders") made concrete.
 *
 * The pipeline has one descriptor set of four storage buffers — 0 rotations,
 * 1 input vectors, 2 output vectors, 3 per-rotation status (uint; a shader
 * may leave it alone) — and 16 bytes of push constants (order, count, form,
 * 0).  A dispatch covers `count` rotations in groups of 64 invocations
 * (the convention's local_size_x).  All buffers are host-visible and
 * coherent: on a CPU device (lavapipe) that is plain memory; on a GPU the
 * kernels checked here are small.  Everything runs in the sandbox's child
 * (plugin.c's pattern), so a shader that hangs or loses the device costs
 * only the child. */
#include "lab/vk_compute.h"
#include "core/shlab_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SHLAB_HAVE_VULKAN
#include <vulkan/vulkan.h>

struct sh_vk {
    VkInstance inst;
    VkPhysicalDevice phys;
    VkDevice dev;
    VkQueue queue;
    uint32_t qfam;
    VkPhysicalDeviceMemoryProperties mem;
    VkDescriptorSetLayout dsl;
    VkPipelineLayout pl;
    VkShaderModule mod;
    VkPipeline pipe;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    VkCommandPool cpool;
    VkCommandBuffer cmd;
    VkFence fence;
    VkBuffer buf[4];
    VkDeviceMemory bmem[4];
    void *map[4];
    VkDeviceSize size[4];
    char device_name[256], driver[256];
    int is_cpu;
};

static int vk_fail(VkResult r, const char *what)
{
    const char *why = r == VK_ERROR_DEVICE_LOST           ? "the device was lost"
                      : r == VK_ERROR_OUT_OF_HOST_MEMORY   ? "out of host memory"
                      : r == VK_ERROR_OUT_OF_DEVICE_MEMORY ? "out of device memory"
                      : r == VK_ERROR_INITIALIZATION_FAILED ? "initialisation failed"
                      : r == VK_ERROR_INCOMPATIBLE_DRIVER  ? "no Vulkan driver (the loader found no ICD)"
                      : r == VK_ERROR_INVALID_SHADER_NV    ? "the shader is invalid"
                      : r == VK_TIMEOUT                    ? "timed out"
                                                           : NULL;
    if (why) return sh_error(SH_EIO, "Vulkan: %s: %s", what, why);
    return sh_error(SH_EIO, "Vulkan: %s: VkResult %d", what, (int)r);
}

/* The device: --device index, or the first GPU, else the first device. */
static int pick_device(sh_vk *v, int want)
{
    uint32_t n = 0;
    VkResult r = vkEnumeratePhysicalDevices(v->inst, &n, NULL);
    if (r != VK_SUCCESS) return vk_fail(r, "enumerating devices");
    if (n == 0) return sh_error(SH_EIO, "Vulkan: no device (install mesa-vulkan-drivers for lavapipe, a CPU device)");
    VkPhysicalDevice ds[16];
    if (n > 16) n = 16;
    vkEnumeratePhysicalDevices(v->inst, &n, ds);
    int pick = -1;
    if (want >= 0) {
        if ((uint32_t)want >= n) return sh_error(SH_EINVAL, "--device %d: this machine has %u Vulkan devices (0..%u)", want, n, n - 1);
        pick = want;
    }
    for (uint32_t i = 0; pick < 0 && i < n; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(ds[i], &p);
        if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU)
            pick = (int)i;
    }
    if (pick < 0) pick = 0;
    v->phys = ds[pick];
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(v->phys, &p);
    v->is_cpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    snprintf(v->device_name, sizeof v->device_name, "%s", p.deviceName);
    VkPhysicalDeviceDriverProperties drv = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &drv};
    vkGetPhysicalDeviceProperties2(v->phys, &p2);
    snprintf(v->driver, sizeof v->driver, "%.120s %.120s", drv.driverName, drv.driverInfo);
    vkGetPhysicalDeviceMemoryProperties(v->phys, &v->mem);
    uint32_t nq = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(v->phys, &nq, NULL);
    VkQueueFamilyProperties qs[16];
    if (nq > 16) nq = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(v->phys, &nq, qs);
    for (uint32_t i = 0; i < nq; i++)
        if (qs[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
            v->qfam = i;
            return SH_OK;
        }
    return sh_error(SH_EIO, "Vulkan: device '%s' has no compute queue", v->device_name);
}

int sh_vk_open(int device, sh_vk **out)
{
    *out = NULL;
    sh_vk *v = calloc(1, sizeof *v);
    if (!v) return sh_error(SH_ENOMEM, "out of memory");
    const VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "shlab",
                                   .apiVersion = VK_API_VERSION_1_1};
    const VkInstanceCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
    VkResult r = vkCreateInstance(&ici, NULL, &v->inst);
    int st = r == VK_SUCCESS ? pick_device(v, device) : vk_fail(r, "creating the instance");
    if (!st) {
        const float prio = 1;
        const VkDeviceQueueCreateInfo qci = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                             .queueFamilyIndex = v->qfam, .queueCount = 1, .pQueuePriorities = &prio};
        const VkDeviceCreateInfo dci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .queueCreateInfoCount = 1,
                                        .pQueueCreateInfos = &qci};
        if ((r = vkCreateDevice(v->phys, &dci, NULL, &v->dev)) != VK_SUCCESS) st = vk_fail(r, "creating the device");
    }
    if (!st) {
        vkGetDeviceQueue(v->dev, v->qfam, 0, &v->queue);
        const VkCommandPoolCreateInfo cp = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                            .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                            .queueFamilyIndex = v->qfam};
        const VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        if ((r = vkCreateCommandPool(v->dev, &cp, NULL, &v->cpool)) != VK_SUCCESS ||
            (r = vkCreateFence(v->dev, &fi, NULL, &v->fence)) != VK_SUCCESS)
            st = vk_fail(r, "creating a command pool");
    }
    if (!st) {
        const VkCommandBufferAllocateInfo ca = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                                .commandPool = v->cpool, .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                                .commandBufferCount = 1};
        if ((r = vkAllocateCommandBuffers(v->dev, &ca, &v->cmd)) != VK_SUCCESS) st = vk_fail(r, "allocating a command buffer");
    }
    if (st) {
        sh_vk_close(v);
        return st;
    }
    *out = v;
    return SH_OK;
}

const char *sh_vk_device_name(const sh_vk *v) { return v->device_name; }
const char *sh_vk_driver(const sh_vk *v) { return v->driver; }
int sh_vk_is_cpu(const sh_vk *v) { return v->is_cpu; }

int sh_vk_pipeline(sh_vk *v, const uint32_t *spirv, size_t nwords, const char *entry)
{
    VkDescriptorSetLayoutBinding b[4];
    for (int i = 0; i < 4; i++)
        b[i] = (VkDescriptorSetLayoutBinding){.binding = (uint32_t)i, .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                              .descriptorCount = 1, .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
    const VkDescriptorSetLayoutCreateInfo dl = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                                .bindingCount = 4, .pBindings = b};
    const VkPushConstantRange pc = {.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .offset = 0, .size = 16};
    VkResult r = vkCreateDescriptorSetLayout(v->dev, &dl, NULL, &v->dsl);
    if (r != VK_SUCCESS) return vk_fail(r, "creating the descriptor set layout");
    const VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, .setLayoutCount = 1,
                                            .pSetLayouts = &v->dsl, .pushConstantRangeCount = 1,
                                            .pPushConstantRanges = &pc};
    if ((r = vkCreatePipelineLayout(v->dev, &pli, NULL, &v->pl)) != VK_SUCCESS) return vk_fail(r, "creating the pipeline layout");
    const VkShaderModuleCreateInfo sm = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                         .codeSize = nwords * 4, .pCode = spirv};
    if ((r = vkCreateShaderModule(v->dev, &sm, NULL, &v->mod)) != VK_SUCCESS) return vk_fail(r, "loading the SPIR-V");
    const VkComputePipelineCreateInfo ci = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = v->mod, .pName = entry},
        .layout = v->pl};
    if ((r = vkCreateComputePipelines(v->dev, VK_NULL_HANDLE, 1, &ci, NULL, &v->pipe)) != VK_SUCCESS)
        return vk_fail(r, "creating the compute pipeline (does the shader follow the convention: set 0, bindings "
                          "0-3, 16 bytes of push constants?)");
    const VkDescriptorPoolSize ps = {.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .descriptorCount = 4};
    const VkDescriptorPoolCreateInfo dp = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, .maxSets = 1,
                                           .poolSizeCount = 1, .pPoolSizes = &ps};
    if ((r = vkCreateDescriptorPool(v->dev, &dp, NULL, &v->pool)) != VK_SUCCESS) return vk_fail(r, "creating a descriptor pool");
    const VkDescriptorSetAllocateInfo da = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                            .descriptorPool = v->pool, .descriptorSetCount = 1, .pSetLayouts = &v->dsl};
    if ((r = vkAllocateDescriptorSets(v->dev, &da, &v->set)) != VK_SUCCESS) return vk_fail(r, "allocating the descriptor set");
    return SH_OK;
}

static void free_buffers(sh_vk *v)
{
    for (int i = 0; i < 4; i++) {
        if (v->map[i]) vkUnmapMemory(v->dev, v->bmem[i]);
        if (v->buf[i]) vkDestroyBuffer(v->dev, v->buf[i], NULL);
        if (v->bmem[i]) vkFreeMemory(v->dev, v->bmem[i], NULL);
        v->map[i] = NULL, v->buf[i] = VK_NULL_HANDLE, v->bmem[i] = VK_NULL_HANDLE, v->size[i] = 0;
    }
}

int sh_vk_buffers(sh_vk *v, const size_t bytes[4], void *map[4])
{
    free_buffers(v);
    VkDescriptorBufferInfo bi[4];
    VkWriteDescriptorSet w[4];
    for (int i = 0; i < 4; i++) {
        const VkDeviceSize sz = bytes[i] < 16 ? 16 : (VkDeviceSize)bytes[i];
        const VkBufferCreateInfo bc = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = sz,
                                       .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
        VkResult r = vkCreateBuffer(v->dev, &bc, NULL, &v->buf[i]);
        if (r != VK_SUCCESS) return vk_fail(r, "creating a buffer");
        VkMemoryRequirements mr;
        vkGetBufferMemoryRequirements(v->dev, v->buf[i], &mr);
        const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        uint32_t type = UINT32_MAX;
        for (uint32_t t = 0; t < v->mem.memoryTypeCount && type == UINT32_MAX; t++)
            if ((mr.memoryTypeBits & (1u << t)) && (v->mem.memoryTypes[t].propertyFlags & want) == want) type = t;
        if (type == UINT32_MAX) return sh_error(SH_EIO, "Vulkan: no host-visible coherent memory on '%s'", v->device_name);
        const VkMemoryAllocateInfo ma = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = mr.size,
                                         .memoryTypeIndex = type};
        if ((r = vkAllocateMemory(v->dev, &ma, NULL, &v->bmem[i])) != VK_SUCCESS) return vk_fail(r, "allocating memory");
        if ((r = vkBindBufferMemory(v->dev, v->buf[i], v->bmem[i], 0)) != VK_SUCCESS) return vk_fail(r, "binding memory");
        if ((r = vkMapMemory(v->dev, v->bmem[i], 0, sz, 0, &v->map[i])) != VK_SUCCESS) return vk_fail(r, "mapping memory");
        v->size[i] = sz;
        map[i] = v->map[i];
        bi[i] = (VkDescriptorBufferInfo){.buffer = v->buf[i], .offset = 0, .range = VK_WHOLE_SIZE};
        w[i] = (VkWriteDescriptorSet){.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, .dstSet = v->set,
                                      .dstBinding = (uint32_t)i, .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .pBufferInfo = &bi[i]};
    }
    vkUpdateDescriptorSets(v->dev, 4, w, 0, NULL);
    return SH_OK;
}

int sh_vk_record(sh_vk *v, int order, int count, int form, int repeat)
{
    const uint32_t pc[4] = {(uint32_t)order, (uint32_t)count, (uint32_t)form, 0};
    vkResetCommandBuffer(v->cmd, 0);
    const VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VkResult r = vkBeginCommandBuffer(v->cmd, &bi);
    if (r != VK_SUCCESS) return vk_fail(r, "recording");
    vkCmdBindPipeline(v->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, v->pipe);
    vkCmdBindDescriptorSets(v->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, v->pl, 0, 1, &v->set, 0, NULL);
    vkCmdPushConstants(v->cmd, v->pl, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof pc, pc);
    const VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT};
    for (int k = 0; k < repeat; k++) {
        if (k)
            vkCmdPipelineBarrier(v->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                                 &mb, 0, NULL, 0, NULL);
        /* count 0: one group whose invocations all return at once (k ≥ count) */
        vkCmdDispatch(v->cmd, count > 0 ? ((uint32_t)count + SH_VK_LOCAL_SIZE - 1) / SH_VK_LOCAL_SIZE : 1, 1, 1);
    }
    const VkMemoryBarrier host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER, .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                  .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(v->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, NULL,
                         0, NULL);
    if ((r = vkEndCommandBuffer(v->cmd)) != VK_SUCCESS) return vk_fail(r, "recording");
    return SH_OK;
}

int sh_vk_submit(sh_vk *v, double timeout_s)
{
    const VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &v->cmd};
    vkResetFences(v->dev, 1, &v->fence);
    VkResult r = vkQueueSubmit(v->queue, 1, &si, v->fence);
    if (r != VK_SUCCESS) return vk_fail(r, "submitting the dispatch");
    r = vkWaitForFences(v->dev, 1, &v->fence, VK_TRUE, (uint64_t)(timeout_s * 1e9));
    if (r == VK_TIMEOUT) return sh_error(SH_EIO, "the shader did not finish within %g s", timeout_s);
    if (r != VK_SUCCESS) return vk_fail(r, "waiting for the dispatch");
    return SH_OK;
}

void sh_vk_close(sh_vk *v)
{
    if (!v) return;
    if (v->dev) {
        vkDeviceWaitIdle(v->dev);
        free_buffers(v);
        if (v->fence) vkDestroyFence(v->dev, v->fence, NULL);
        if (v->cpool) vkDestroyCommandPool(v->dev, v->cpool, NULL);
        if (v->pool) vkDestroyDescriptorPool(v->dev, v->pool, NULL);
        if (v->pipe) vkDestroyPipeline(v->dev, v->pipe, NULL);
        if (v->mod) vkDestroyShaderModule(v->dev, v->mod, NULL);
        if (v->pl) vkDestroyPipelineLayout(v->dev, v->pl, NULL);
        if (v->dsl) vkDestroyDescriptorSetLayout(v->dev, v->dsl, NULL);
        vkDestroyDevice(v->dev, NULL);
    }
    if (v->inst) vkDestroyInstance(v->inst, NULL);
    free(v);
}

int sh_vk_available(void) { return 1; }

#else /* no Vulkan headers at build time */

struct sh_vk { int unused; };
static int absent(void)
{
    return sh_error(SH_ENOTSUP, "shlab was built without Vulkan (Debian: libvulkan-dev, mesa-vulkan-drivers; then make)");
}
int sh_vk_open(int device, sh_vk **out) { (void)device; *out = NULL; return absent(); }
const char *sh_vk_device_name(const sh_vk *v) { (void)v; return ""; }
const char *sh_vk_driver(const sh_vk *v) { (void)v; return ""; }
int sh_vk_is_cpu(const sh_vk *v) { (void)v; return 0; }
int sh_vk_pipeline(sh_vk *v, const uint32_t *spirv, size_t nwords, const char *entry) { return absent(); }
int sh_vk_buffers(sh_vk *v, const size_t bytes[4], void *map[4]) { return absent(); }
int sh_vk_record(sh_vk *v, int order, int count, int form, int repeat) { return absent(); }
int sh_vk_submit(sh_vk *v, double timeout_s) { return absent(); }
void sh_vk_close(sh_vk *v) { (void)v; }
int sh_vk_available(void) { return 0; }

#endif
