/*
 * STAND-IN for Zephyr's <zephyr/bluetooth/conn.h>: the connection names FreeBot's main.c uses,
 * with Zephyr's signatures. BT_CONN_CB_DEFINE registers its callbacks as Zephyr's does (there:
 * an iterable section; here: one pointer, so at most one BT_CONN_CB_DEFINE per program), and the
 * test driver (freebot_driver.c) calls its `connected` once, as a phone connecting. Not Zephyr.
 */
#ifndef FREEBOT_STANDIN_BT_CONN_H
#define FREEBOT_STANDIN_BT_CONN_H

#include <stdbool.h>
#include <stdint.h>
#include <zephyr/bluetooth/addr.h>

struct bt_conn;

typedef enum { BT_SECURITY_L0, BT_SECURITY_L1, BT_SECURITY_L2, BT_SECURITY_L3, BT_SECURITY_L4 } bt_security_t;
enum bt_security_err { BT_SECURITY_ERR_SUCCESS, BT_SECURITY_ERR_AUTH_FAIL, BT_SECURITY_ERR_UNSPECIFIED };

struct bt_conn_cb {
    void (*connected)(struct bt_conn *conn, uint8_t err);
    void (*disconnected)(struct bt_conn *conn, uint8_t reason);
    void (*security_changed)(struct bt_conn *conn, bt_security_t level, enum bt_security_err err);
};

extern const struct bt_conn_cb *z_bt_conn_cb;   /* the one BT_CONN_CB_DEFINE's */
#define BT_CONN_CB_DEFINE(_name) \
    static const struct bt_conn_cb _name; \
    const struct bt_conn_cb *z_bt_conn_cb = &_name; \
    static const struct bt_conn_cb _name

struct bt_conn_auth_cb {
    void (*passkey_display)(struct bt_conn *conn, unsigned int passkey);
    void (*passkey_entry)(struct bt_conn *conn);
    void (*passkey_confirm)(struct bt_conn *conn, unsigned int passkey);
    void (*cancel)(struct bt_conn *conn);
};

struct bt_conn_auth_info_cb {
    void (*pairing_complete)(struct bt_conn *conn, bool bonded);
    void (*pairing_failed)(struct bt_conn *conn, enum bt_security_err reason);
};

struct bt_conn *bt_conn_ref(struct bt_conn *conn);
void bt_conn_unref(struct bt_conn *conn);
const bt_addr_le_t *bt_conn_get_dst(const struct bt_conn *conn);
int bt_conn_auth_cb_register(const struct bt_conn_auth_cb *cb);
int bt_conn_auth_info_cb_register(struct bt_conn_auth_info_cb *cb);
int bt_conn_auth_passkey_confirm(struct bt_conn *conn);
int bt_conn_auth_cancel(struct bt_conn *conn);

#endif
