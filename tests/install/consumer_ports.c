/*
 * tests/install/consumer_ports.c - built by `make install-check` against the INSTALLED port
 * headers and libqorient_ports.a through pkg-config (qorient-ports.pc): parses a register map
 * held in memory, records two ticks through the mock sink and checks what arrived. Exits 0
 * and prints one line when everything holds, else names the failed check and exits 1.
 */
#include <stdio.h>
#include <string.h>

#include "linux/regmap.h"
#include "linux/modbus_sink.h"
#include "linux/streamer.h"
#include "mock/mock_sink.h"

static const char map_text[] =
    "[slave.1]\nmax_registers = 123\n"
    "[joint.pan]\nslave = 1\naddress = 0\ntype = int32\nscale = 1000\n"
    "[joint.tilt]\nslave = 1\naddress = 2\ntype = int16\nscale = 100\n";

int main(void)
{
    static qo_regmap map;
    qo_modbus_link_spec spec;
    char err[128];
    qo_status s;

    s = qo_regmap_parse(map_text, "consumer.ini", &map, err, sizeof err);
    if (s != QO_OK || map.n_joints != 2 || strcmp(map.joints[1].name, "tilt") != 0) {
        printf("consumer_ports: FAIL: register map: %s (%s), %zu joints\n", qo_status_str(s), err,
               map.n_joints);
        return 1;
    }
    s = qo_modbus_link_parse_spec("rtu:/dev/ttyAMA0,115200,8N1", &spec);
    if (s != QO_OK || spec.transport != QO_MODBUS_LINK_RTU || spec.baud != 115200 ||
        spec.parity != 'N') {
        printf("consumer_ports: FAIL: qo_modbus_link_parse_spec: %s\n", qo_status_str(s));
        return 1;
    }
    {
        float values[4];
        const float a[2] = { 0.5f, -0.25f }, b[2] = { 0.75f, 0.0f };
        const float *row;
        qo_mock_sink m;
        qo_sink sink;
        if (qo_mock_sink_open(&m, 2, values, NULL, 2) != QO_OK ||
            qo_mock_sink_as_sink(&m, &sink) != QO_OK ||
            qo_sink_write(&sink, a, 2, 0) != QO_OK || qo_sink_write(&sink, b, 2, 1) != QO_OK ||
            (row = qo_mock_sink_row(&m, 1)) == NULL || row[0] != 0.75f || row[1] != 0.0f) {
            printf("consumer_ports: FAIL: the mock sink did not record two ticks\n");
            return 1;
        }
    }
    printf("consumer_ports: qorient-ports: map of %zu joints (%s, %s), RTU spec %s %d baud, "
           "mock sink: ok\n",
           map.n_joints, map.joints[0].name, map.joints[1].name, spec.device, spec.baud);
    return 0;
}
